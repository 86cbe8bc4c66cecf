% The Prolog expert's driver, shipped inside proclaim and run by SWI-Prolog: it speaks the
% program expert's JSON-lines protocol (README, "Any program as an expert") on stdin and
% stdout, loads the knowledge base it is sent, keeps each whiteboard input as the fact
% value(Type, Value) and proves each label it answers as the goal of that name, within a
% time limit. Anything the knowledge base prints goes to stderr, so stdout stays protocol.

:- module(proclaim_driver, [main/0]).
:- use_module(library(http/json)).
:- use_module(library(time)).

:- dynamic user:value/2.
:- dynamic label/1, last/2, protocol_out/1, time_limit/1, load_file/1, input_seq/1.

% The seq of the last input taken in (0 before any): an answer given unasked says it.
input_seq(0).

time_limit(0.2).

main :-
    current_output(Out),
    asserta(protocol_out(Out)),
    set_stream(Out, encoding(utf8)),
    set_stream(user_input, encoding(utf8)),
    % What the knowledge base writes to standard output goes to stderr.
    set_stream(user_error, alias(user_output)),
    set_output(user_error),
    set_prolog_flag(unknown, error),
    loop.

loop :-
    read_line_to_string(user_input, Line),
    (   Line == end_of_file
    ->  true
    ;   catch(atom_json_dict(Line, Message, [value_string_as(atom)]), _, fail)
    ->  handle(Message.get(type, none), Message),
        loop
    ;   reply(_{warning: "the driver read a line that is not JSON"}),
        loop
    ).

handle(hello, Message) :- !,
    retractall(label(_)),
    forall(member(L, Message.get(answers, [])), assertz(label(L))).
handle(load, Message) :- !,
    (   Limit = Message.get(time_limit), number(Limit)
    ->  retractall(time_limit(_)), assertz(time_limit(Limit))
    ;   true
    ),
    load_knowledge(Message.file, Message.text),
    reply(_{ready: true}),
    prove_changed.
handle(input, Message) :- !,
    Name = Message.name,
    retractall(input_seq(_)),
    assertz(input_seq(Message.get(seq, 0))),
    retractall(user:value(Name, _)),
    (   Message.get(value, null) == null
    ->  true
    ;   assertz(user:value(Name, Message.value))
    ),
    prove_changed.
handle(query, Message) :- !,
    Label = Message.label,
    prove(Label, Result),
    retractall(last(Label, _)),
    assertz(last(Label, Result)),
    answer(Label, Result, _{id: Message.get(id, null)}).
handle(Type, _) :-
    format(string(Text), "the driver does not know messages of type ~w", [Type]),
    reply(_{warning: Text}).

% Loads the text as the file it names; every error and warning of the load comes back as a
% located warning, through message_hook/3 below.
load_knowledge(File, Text) :-
    retractall(load_file(_)),
    assertz(load_file(File)),
    time_limit(Limit),
    LoadLimit is max(Limit * 50, 1),
    setup_call_cleanup(
        open_string(Text, Stream),
        catch(call_with_time_limit(LoadLimit,
                                   load_files(user:File, [stream(Stream), silent(true)])),
              Error,
              load_failed(File, Error)),
        (   close(Stream),
            retractall(load_file(_))
        )),
    forall(label(L),
           (   atom(L), current_predicate(user:L/0)
           ->  true
           ;   format(string(W), "label `~w` is not defined here (write a clause `~w :- ...`)", [L, L]),
               reply(_{warning: W, file: File, line: 1})
           )).

load_failed(File, time_limit_exceeded) :- !,
    time_limit(Limit),
    LoadLimit is max(Limit * 50, 1),
    format(string(Text), "loading took longer than its time limit of ~w s (a directive that never ends?)", [LoadLimit]),
    reply(_{warning: Text, file: File, line: 1}).
load_failed(File, Error) :-
    message_text(Error, Text),
    reply(_{warning: Text, file: File, line: 1}).

% Errors and warnings while loading (while load_file/1 names the file) come back located: at
% the place SWI-Prolog's message names (`file:line:column: text`), else where the loader is.
% Afterwards SWI-Prolog prints them as it would.
:- multifile user:message_hook/3.
user:message_hook(Term, Kind, Lines) :-
    memberchk(Kind, [error, warning]),
    load_file(File),
    !,
    lines_text(Lines, Text0),
    (   located(Text0, File, Line, Column, Text)
    ->  reply(_{warning: Text, file: File, line: Line, column: Column})
    ;   message_line(Term, Line)
    ->  reply(_{warning: Text0, file: File, line: Line})
    ;   reply(_{warning: Text0, file: File, line: 1})
    ).

lines_text(Lines, Text) :-
    with_output_to(string(Text0), print_message_lines(current_output, '', Lines)),
    split_string(Text0, "", "\n ", [Text]).

% `File:Line:Column: Text` or `File:Line: Text`.
located(Full, File, Line, Column, Text) :-
    string_concat(File, Rest0, Full),
    string_concat(":", Rest1, Rest0),
    split_string(Rest1, ":", "", [LineText|Parts]),
    number_string(Line, LineText),
    (   Parts = [ColumnText|More], number_string(Column0, ColumnText), More \== []
    ->  Column is Column0 + 1,              % SWI-Prolog counts columns from 0
        atomic_list_concat(More, ':', Text1)
    ;   Column = 0, atomic_list_concat(Parts, ':', Text1)
    ),
    split_string(Text1, "", " ", [Text]).

message_line(error(_, file(_, Line, _, _)), Line) :- !.
message_line(error(_, stream(_, Line, _, _)), Line) :- !.
message_line(_, Line) :-
    source_location(_, Line).

% Proves every label and answers those whose result changed.
prove_changed :-
    forall(label(L),
           (   prove(L, Result),
               (   last(L, Result)
               ->  true
               ;   retractall(last(L, _)),
                   assertz(last(L, Result)),
                   input_seq(Seq),
                   answer(L, Result, _{after: Seq})
               )
           )).

prove(Label, Result) :-
    time_limit(Limit),
    catch(call_with_time_limit(Limit,
                               (   call(user:Label)
                               ->  Result = true
                               ;   Result = false
                               )),
          Error,
          (   message_text(Error, Text), Result = error(Text) )).

% An answer; to a query, with its id.
answer(Label, error(Text), Id) :- !,
    reply(Id.put(_{label: Label, error: Text})).
answer(Label, Value, Id) :-
    reply(Id.put(_{label: Label, value: Value})).

message_text(time_limit_exceeded, Text) :- !,
    time_limit(Limit),
    format(string(Text), "no answer within the time limit of ~w s", [Limit]).
message_text(Error, Text) :-
    catch('$messages':translate_message(Error, Lines, []), _, fail), !,
    lines_text(Lines, Text).
message_text(Error, Text) :-
    format(string(Text), "~q", [Error]).

reply(Dict) :-
    protocol_out(Out),
    json_write_dict(Out, Dict, [width(0)]),
    nl(Out),
    flush_output(Out).
