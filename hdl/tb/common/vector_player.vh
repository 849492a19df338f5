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

// Never counted by coverage (the testbenches say why).
/* verilator coverage_off */
localparam WORDS = 1 + N_IN + 2 * N_OUT;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] mem [0:MAX_WORDS-1];
integer records;
integer rec;
integer last_cycle;
integer cycle;
// Time: the falling edge that releases reset, at t_release, ends the last
// reset cycle; cycle c is compared at the falling edge that ends it,
// t_release + (c + 1) * PERIOD_FS.
localparam [63:0] PERIOD_FS = 64'd2 * HALF_PERIOD_FS;
reg [63:0] t_release;
integer stop;
integer change_cycle;
reg woken_by_change;
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
    repeat (3) @(posedge clk);
    @(negedge clk);
    t_release = $time;
    apply_inputs;
    load_expected;
    record_started = 1'b1;
    rst = 1'b0;
    cycle = -1;
    // Until the last cycle's compare; the loop, not $finish, ends the
    // process: Verilator runs on after $finish to the next wait, and there
    // is none at the last cycle.
    while (cycle != last_cycle) begin
        // The next compare due whatever the outputs do: the first cycle of
        // a record (its expectation is new), the cycle before the next
        // record (its inputs are driven right after that compare), or the
        // last cycle.
        if (record_started) begin
            stop = cycle + 1;
        end else begin
            stop = last_cycle;
            if (rec + 1 < records && mem[(rec + 1) * WORDS] - 1 < stop)
                stop = mem[(rec + 1) * WORDS] - 1;
        end
        // An output that already differs from the last check (driven by
        // the inputs just applied) is compared at the next falling edge.
        if (stop == cycle + 1 || all_outputs !== outputs_checked) begin
            #(PERIOD_FS);
            cycle = cycle + 1;
        end else begin
            // Until then, wait for the first output change, not cycle by
            // cycle: the cycles between compare as the last one did
            // (below).
            woken_by_change = 1'b0;
`ifdef VERILATOR
            // Disabling a fork is unsupported in Verilator 5.006 ("disable
            // fork"): it looks at each falling edge instead, which costs it
            // little.
            while (!woken_by_change && cycle < stop) begin
                #(PERIOD_FS);
                cycle = cycle + 1;
                woken_by_change = (all_outputs !== outputs_checked);
            end
`else
            fork : wait_for_change
                begin
                    #((stop - cycle) * PERIOD_FS);
                    disable wait_for_change;
                end
                begin
                    @(all_outputs);
                    woken_by_change = 1'b1;
                    disable wait_for_change;
                end
            join
            if (!woken_by_change) begin
                cycle = stop;
            end else begin
                // A change in cycle c (at its rising edge, or at the falling
                // edge that ends cycle c - 1, where inputs are driven) is
                // first seen by the compare that ends cycle c.
                change_cycle = ($time - t_release) / PERIOD_FS;
                cycle = (change_cycle < stop) ? change_cycle : stop;
                if (t_release + (cycle + 1) * PERIOD_FS > $time)
                    #(t_release + (cycle + 1) * PERIOD_FS - $time);
            end
`endif
        end
        // Each cycle's outcome is that of comparing every output with its
        // expected value under its mask. When no output has changed (!==:
        // an X or Z that comes or goes is a change) and the record, hence
        // the expectation, is the same as at the last check, that outcome is
        // the last check's, a pass: check_outputs runs only when one of them
        // changed, and the loop above sleeps through the cycles where
        // neither can happen. Most cycles of a replay change nothing (a core
        // counting down a wait): waking at every falling edge cost Icarus
        // 5 % (EnDat, ESL) to 27 % (CANopen) of a replay.
        if (record_started || all_outputs !== outputs_checked) begin
            check_outputs;
            outputs_checked = all_outputs;
            record_started = 1'b0;
        end
        if (cycle != last_cycle && rec + 1 < records && mem[(rec + 1) * WORDS] == cycle + 1) begin
            rec = rec + 1;
            apply_inputs;
            load_expected;
            record_started = 1'b1;
        end
    end
    $display("PASS: %0s: %0d cycles, %0d records, every output compared every cycle",
             vector_file, cycle + 1, records);
    $finish;
end
