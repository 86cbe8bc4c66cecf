% The off-side rule of the seed paper, in Prolog beside offside.dl: "Usually a player is not
% off-side, unless fewer than two opponents are between the player and the goal line, unless
% the player is in its own half, or behind the ball, or received the ball directly from a
% throw-in." Each input is the fact value(Input, true | false); an input never posted has none.
% The Prolog expert proves the label `offside` as this goal (crates/experts/tests/programs.rs
% checks it against every row of offside.dl's truth table); machines/referee runs it.

offside :-
    holds(fewerThanTwoOpponentsBetween),
    \+ excused.

excused :- holds(inOwnHalf).
excused :- holds(behindBall).
excused :- holds(fromThrowIn).

holds(Input) :- value(Input, true).
