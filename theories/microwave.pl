% The one-minute microwave of microwave.dl in Prolog: the magnetron cooks while there is time
% left and the door is shut; the light is on while the door is open or the magnetron cooks.
% The whiteboard bench (benches/board.rs) asks it beside the CDL reasoner.

cook :- value(timeLeft, true), \+ value(doorOpen, true).

light :- value(doorOpen, true).
light :- cook.
