// tb_rnd.vh: included inside both testbenches (a module item, not a module).
/* xorshift32: the same numbers in both simulators ($random(seed) differs) */
reg [31:0] rnd_state;
reg [31:0] r1, r2;
task rnd(output [31:0] r);
    begin
        rnd_state = rnd_state ^ (rnd_state << 13);
        rnd_state = rnd_state ^ (rnd_state >> 17);
        rnd_state = rnd_state ^ (rnd_state << 5);
        r = rnd_state;
    end
endtask
