#!/usr/bin/env python3
"""Writes the published models of this folder in the IR text form (run from this folder).

leader_sync_N_K.ir: the synchronous leader election of Itai and Rodeh, as PRISM's case study
leader_sync models it (one IR rule per synchronised action). herman(9, "010010010") writes Herman's
self-stabilising ring of 9 processes from three equally spaced tokens (146 KB, so not kept here:
tests/unit/markov_test.cpp builds it). The tests assert the published figures."""


def leader_sync(n, k):
    nxt = lambda i: i % n + 1
    t = [f"# The synchronous leader election of Itai and Rodeh, N = {n} processes, ids 0..{k - 1}.",
         "# Written by make_models.py. Each round every process picks an id (one rule, K^N outcomes), the ids",
         "# travel round the ring (read, N - 1 times), then all decide: a unique id (done) or again (retry).",
         "semo-ir 1;", f"var c : 1..{n - 1} = 1;"]
    for i in range(1, n + 1):
        t += [f"var s{i} : 0..3;", f"var u{i} : bool;", f"var v{i} : 0..{k - 1};", f"var p{i} : 0..{k - 1};"]
    every = lambda fmt: " && ".join(fmt.format(i=i) for i in range(1, n + 1))
    unique = " || ".join(f"u{i}" for i in range(1, n + 1))
    outcomes = []
    for o in range(k ** n):
        ids, rest = [], o
        for i in range(1, n + 1):
            ids.append(rest % k)
            rest //= k
        sets = ", ".join(f"s{i}' = 1, p{i}' = {ids[i - 1]}, v{i}' = {ids[i - 1]}, u{i}' = true" for i in range(1, n + 1))
        outcomes.append(f"1/{k ** n} : {sets}")
    t.append(f"rule pick : {every('s{i} == 0')} ->\n    " + "\n  + ".join(outcomes) + ";")
    last = f"c == {n - 1}"
    reads = [f"c' = ({last} ? c : c + 1)"]
    for i in range(1, n + 1):
        j = nxt(i)
        reads += [f"s{i}' = ({last} ? 2 : 1)", f"u{i}' = (u{i} ? p{i} != v{j} : false)", f"v{i}' = ({last} ? 0 : v{j})",
                  f"p{i}' = ({last} ? (u{i} ? 0 : p{i}) : (u{i} ? p{i} : 0))"]
    t.append(f"rule read : {every('s{i} == 1')} -> " + ", ".join(reads) + ";")
    reset = ", ".join(f"u{i}' = false, v{i}' = 0, p{i}' = 0" for i in range(1, n + 1))
    t.append(f"rule done : {every('s{i} == 2')} && ({unique}) -> " + ", ".join(f"s{i}' = 3" for i in range(1, n + 1)) + f", {reset};")
    t.append(f"rule retry : {every('s{i} == 2')} && !({unique}) -> c' = 1, " + ", ".join(f"s{i}' = 0" for i in range(1, n + 1)) + f", {reset};")
    t.append(f"rule loop : {every('s{i} == 3')} -> skip;")
    t.append(f"property elected : eventually {{{every('s{i} == 3')}}};")
    return "\n".join(t) + "\n"


def herman(n, initial):
    t = [f"# Herman's self-stabilising ring of {n} processes: a process holds a token when its bit equals its",
         "# left neighbour's; each step, all at once, a token holder flips a fair coin and the others copy their",
         "# neighbour. Starts from three equally spaced tokens. Written by make_models.py.", "semo-ir 1;"]
    t += [f"var x{i} : bool = {'true' if initial[i] == '1' else 'false'};" for i in range(n)]
    outcomes = []
    for o in range(2 ** n):
        sets = ", ".join(f"x{i}' = (x{i} == x{(i - 1) % n} ? {'true' if o >> i & 1 else 'false'} : x{(i - 1) % n})" for i in range(n))
        outcomes.append(f"1/{2 ** n} : {sets}")
    t.append("rule step : true ->\n    " + "\n  + ".join(outcomes) + ";")
    tokens = " + ".join(f"(x{i} == x{(i - 1) % n})" for i in range(n))
    t.append(f"property stabilises : eventually {{{tokens} == 1}};")
    return "\n".join(t) + "\n"


if __name__ == "__main__":
    open("leader_sync_4_4.ir", "w").write(leader_sync(4, 4))
