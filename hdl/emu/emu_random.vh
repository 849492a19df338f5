// emu_random.vh: random numbers for a closed-loop testbench, the same
// sequence in Icarus and in Verilator (xorshift64, Marsaglia 2003).
//
// Why not $random(seed): Verilator 5.006 returns runs of ones from it for a
// small seed (1 gives ff7fffff 01ffffff 03ffffff 07ffffff ...), so runs in
// that simulator would read almost the same positions again and again, and
// the two simulators would test different values. (No comment line here may
// begin with that simulator's name: it would be read as a directive.)
//
// Include it inside the testbench module, seed it once, then draw:
//   `include "emu_random.vh"
//   initial begin
//       random_seed(seed);                    // any integer, 0 included
//       position = random64(0) & mask;
//       flags = random32(0);
//   end
// The argument is unused (Verilog-2005 functions need one). Draw once per
// expression: the simulators evaluate {random32(0), random32(0)} in
// different orders (the language leaves it open), random64 does not.

reg [63:0] random_state = 64'h9E37_79B9_7F4A_7C15;

// The state is never 0 (xorshift would stay there): the seed is mixed into
// a non-zero constant, and 0 is replaced.
task random_seed(input integer seed);
    begin
        random_state = 64'h9E37_79B9_7F4A_7C15 ^ {seed, ~seed};
        if (random_state == 64'd0)
            random_state = 64'h9E37_79B9_7F4A_7C15;
    end
endtask

// The next 32 random bits (the high half of the state: the better bits).
function [31:0] random32(input integer unused);
    begin
        random_state = random_state ^ (random_state << 13);
        random_state = random_state ^ (random_state >> 7);
        random_state = random_state ^ (random_state << 17);
        random32 = random_state[63:32];
    end
endfunction

// The next 64 random bits: two draws in a fixed order.
function [63:0] random64(input integer unused);
    reg [31:0] high;
    begin
        high = random32(0);
        random64 = {high, random32(0)};
    end
endfunction
