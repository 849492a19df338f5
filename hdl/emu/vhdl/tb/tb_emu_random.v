// tb_emu_random: draws of emu_random.vh, one per line in hex, for the
// comparison with emu_random_pkg.vhd (tb_emu_random.vhd prints the same
// draws; scripts/vhdl_examples.sh compares the two outputs).
module tb_emu_random;
`include "emu_random.vh"
integer i;
initial begin
    random_seed(-5);
    for (i = 0; i < 6; i = i + 1)
        $display("%h", random32(0));
    $display("%h", random64(0));
    random_seed(0);
    $display("%h", random32(0));
    random_seed(7);
    $display("%h", random64(0));
end
endmodule
