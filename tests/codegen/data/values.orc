// The data of the plan language through the generated C: valued inputs of every type, integer
// and real arithmetic at its limits (overflow, division by zero, non-finite results), vectors,
// strings, pre, combine, counters and timers. tests/codegen/test_values.py runs hypothesis
// scripts on it and compares the C with the Python runtime instant by instant.
mission Values {
    input N : int := 1, D : int, X : float, Y : float := 2.0, B : bool, S : string := "low",
          V : vector := [0.0, 0.0, 0.0], Go, Reset;
    output Sum : int := 0 combine +, Quot : int, Prod : int, Neg : int, Ratio : float,
           Mixed : float, Scaled : vector, Shift : vector, Same : bool, Flag : bool,
           Name : string, Low : int combine min, Count : int := 0, Late, Cmp : bool,
           Prev : int, Total : float := 0.0 combine +, Tick2;
    var n := 0;
    var k := 1.5;
    par {
        loop {
            par {
                if N { emit Sum(?N); emit Sum(1); emit Low(?N); emit Low(3); emit Prev(pre(?Sum)); }
            } || {
                if N and D { emit Quot(?N / ?D); emit Prod(?N * ?D); emit Neg(-?N - ?D); }
            } || {
                if X { emit Ratio(?X / ?Y); emit Mixed(?X * 2 + ?N); emit Total(?X); emit Total(1.25); }
            } || {
                if V { emit Scaled(?X * ?V); emit Shift(?V + [1.0, -1.0, 0.5]);
                       emit Same(?V == [0.0, 0.0, 0.0]); }
            } || {
                if B { emit Flag(?B and (?N > 2 or not ?B)); emit Cmp(?X < ?N); }
            } || {
                if S { if ?S < "m" { emit Name("early"); } else { emit Name(?S); } }
            } || {
                if Go {
                    n := n + ?N; k := k * ?X; emit Count(pre(?Count) + 1);
                    if n > 100 { emit Late; }
                } else if Reset { n := 0; }
            }
            pause;
        }
    } || {
        loop { await 2 s; emit Tick2; }
    }
}
