// vector_player.vh: the golden-vector replay loop every core's testbench includes.
//
// The including module defines, before the `include:
//   localparam N_IN, N_OUT       number of input and output ports in the vector file
//   localparam OUT_BITS          total width of the outputs
//   parameter  HALF_PERIOD_FS    half the system-clock period in femtoseconds
//   parameter  MAX_WORDS         size of the vector memory in 64-bit words
//   task apply_inputs;           drives the DUT inputs from record `rec` (use `IN_WORD(k))
//   task check_outputs;          compares every output with `CHECK (below)
//   wire [OUT_BITS-1:0] all_outputs   every output checked, concatenated
// and instantiates the DUT on clk / rst.
//
// Vector format (docs/vectors.md): each record is 1 + N_IN + 2*N_OUT words:
//   cycle, inputs..., then (expected, mask) per output. Plusargs:
//   +vectors=<file.hex>  +records=<count>  [+waves=<file.vcd>]
//
// Timing: reset is held for 3 clocks and released at a falling edge; the next
// rising edge is cycle 0. Inputs of a record are driven at the falling edge
// before the rising edge of their cycle; outputs are compared at the falling
// edge after it. The run passes when the last record's cycle has been
// compared, and stops at the first mismatch with cycle, signal, expected and
// actual, exiting non-zero ($fatal) in Icarus and in Verilator.

localparam WORDS = 1 + N_IN + 2 * N_OUT;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] mem [0:MAX_WORDS-1];
integer records;
integer rec;
integer last_cycle;
integer cycle;
integer compared;
// The outputs as check_outputs last saw them, and whether a record has
// started since: see the replay loop.
reg [OUT_BITS-1:0] outputs_checked;
reg record_started;
reg [8*1024-1:0] vector_file;
reg [8*1024-1:0] wave_file;

// Word k of the current record's inputs, and the expected value and mask of output k.
`define IN_WORD(k) mem[rec * WORDS + 1 + (k)]
// The expected values and masks are those of the current record, copied
// out of `mem` when the record starts (load_expected): the compare of every
// cycle then reads a small array at a constant index instead of working out
// a `mem` address per output, which was over half of an Icarus replay's time.
`define EXP_WORD(k) exp_word[k]
`define MASK_WORD(k) mask_word[k]

reg [63:0] exp_word [0:N_OUT-1];
reg [63:0] mask_word [0:N_OUT-1];
integer out_k;

task load_expected;
    begin
        for (out_k = 0; out_k < N_OUT; out_k = out_k + 1) begin
            exp_word[out_k] = mem[rec * WORDS + 1 + N_IN + 2 * out_k];
            mask_word[out_k] = mem[rec * WORDS + 2 + N_IN + 2 * out_k];
        end
    end
endtask

// Compares output k (named name) with its expected value under its mask.
// `!==` so that an X or Z from the DUT is a mismatch, never a silent pass.
`define CHECK(k, name, sig) \
    if ((((64'd0 | (sig)) ^ `EXP_WORD(k)) & `MASK_WORD(k)) !== 64'd0) \
        mismatch(name, `EXP_WORD(k), 64'd0 | (sig), `MASK_WORD(k));

task mismatch(input [8*32-1:0] name, input [63:0] expected, input [63:0] actual, input [63:0] mask);
    begin
        $display("MISMATCH at cycle %0d (record %0d): signal %0s expected %0h actual %0h (mask %0h)",
                 cycle, rec, name, expected, actual, mask);
        $fatal(1, "vectors %0s: the core does not match the model", vector_file);
    end
endtask

initial begin
    if (!$value$plusargs("vectors=%s", vector_file)) begin
        $fatal(1, "missing +vectors=<file.hex>");
    end
    if (!$value$plusargs("records=%d", records)) begin
        $fatal(1, "missing +records=<count> (the 'records:' line of the vector file's header)");
    end
    if (records < 1 || records * WORDS > MAX_WORDS) begin
        $fatal(1, "+records=%0d does not fit MAX_WORDS=%0d at %0d words per record", records, MAX_WORDS, WORDS);
    end
    if ($value$plusargs("waves=%s", wave_file)) begin
        $dumpfile(wave_file);
        $dumpvars(0);
    end
    mem[records * WORDS - 1] = 64'hxxxx_xxxx_xxxx_xxxx;
    $readmemh(vector_file, mem, 0, records * WORDS - 1);
    if (^mem[records * WORDS - 1] === 1'bx) begin
        $fatal(1, "%0s holds fewer than %0d records of %0d words", vector_file, records, WORDS);
    end
    if (mem[0] !== 64'd0) begin
        $fatal(1, "%0s: the first record must be at cycle 0", vector_file);
    end
    // Cycle stamps strictly increase. In a 2-state simulator (Verilator) the
    // words a short file leaves unread are 0, which this catches; in a
    // 4-state one (Icarus) they are x, which the check above catches.
    for (rec = 1; rec < records; rec = rec + 1) begin
        if (!(mem[rec * WORDS] > mem[(rec - 1) * WORDS])) begin
            $fatal(1, "%0s holds fewer than %0d records, or its cycle stamps do not increase at record %0d",
                   vector_file, records, rec);
        end
    end
    last_cycle = mem[(records - 1) * WORDS];
    rec = 0;
    cycle = 0;
    compared = 0;
    repeat (3) @(posedge clk);
    @(negedge clk);
    apply_inputs;
    load_expected;
    record_started = 1'b1;
    rst = 1'b0;
    forever begin
        @(negedge clk);
        // Each cycle's outcome is that of comparing every output with its
        // expected value under its mask. When no output has changed (!==:
        // an X or Z that comes or goes is a change) and the record, hence
        // the expectation, is the same as at the last check, that outcome is
        // the last check's, a pass: check_outputs runs only when one of them
        // changed. Most cycles of a replay change nothing (a core counting
        // down a wait), and the 64-bit compare of each output was a third of
        // an Icarus replay's time (esl_eeprom_page_write_read: 97 s -> 69 s
        // with the compare left out).
        if (record_started || all_outputs !== outputs_checked) begin
            check_outputs;
            outputs_checked = all_outputs;
            record_started = 1'b0;
        end
        compared = compared + 1;
        if (cycle == last_cycle) begin
            $display("PASS: %0s: %0d cycles, %0d records, every output compared every cycle",
                     vector_file, compared, records);
            $finish;
        end
        cycle = cycle + 1;
        if (rec + 1 < records && mem[(rec + 1) * WORDS] == cycle) begin
            rec = rec + 1;
            apply_inputs;
            load_expected;
            record_started = 1'b1;
        end
    end
end
