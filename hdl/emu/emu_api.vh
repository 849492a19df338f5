// emu_api.vh: the emulator library's calls, one spelling for Verilator
// (DPI-C, straight into libcosim) and Icarus (VPI system functions of
// hdl/emu/vpi/emu_vpi.c). Included inside each hdl/emu wrapper module; the
// wrapper's handle is `emu_handle`.
//
// Strings (status names, fault tables) pass as wide regs, 8 bits per
// character; the library trims the leading spaces/NULs such a reg carries.

`ifdef VERILATOR
import "DPI-C" function int emu_open(input string kind, input string path, input longint f_emu_hz);
import "DPI-C" function int emu_step(input int handle, input int pins);
import "DPI-C" function int emu_set_position(input int handle, input int device, input longint position);
import "DPI-C" function int emu_set_status(input int handle, input int device, input string name, input int value);
import "DPI-C" function int emu_schedule_fault(input int handle, input string toml);
import "DPI-C" function int emu_set_motion(input int handle, input int device, input string toml);
import "DPI-C" function longint emu_count(input int handle);
import "DPI-C" function longint emu_last_value(input int handle, input int device);
import "DPI-C" function int emu_last_status(input int handle, input int device, input string name);
import "DPI-C" function int emu_write_transcript(input int handle, input string path);
import "DPI-C" function string emu_last_error();
import "DPI-C" function longint emu_violations(input int handle);
import "DPI-C" function string emu_take_violation(input int handle);
`endif

// String arguments: SystemVerilog strings in Verilator, wide regs in Icarus.
`ifndef EMU_STR
`ifdef VERILATOR
`define EMU_STR string
`else
`define EMU_STR reg [8*1024-1:0]
`endif
`endif

integer emu_handle = 0;

/* Failures: print the library's message with time and instance, then stop */
task emu_fail(input [8*40-1:0] what);
    begin
`ifdef VERILATOR
        $display("ERROR: %0s at time %0t in %m: %0s", what, $time, emu_last_error());
`else
        // The VPI module has printed the message with the time already.
        $display("ERROR: %0s failed in %m (message above)", what);
`endif
        $fatal(1, "emulator stopped the simulation");
    end
endtask

// One step of the emulator: pins in, pins out (< 0 on failure). A macro,
// not a function: an Icarus function call on every emulator cycle cost an
// eighth of a closed loop (SSI with its monitor, 300 reads: 6.0 s -> 5.3 s).
`ifndef EMU_STEP
`ifdef VERILATOR
`define EMU_STEP(pins) emu_step(emu_handle, pins)
`else
`define EMU_STEP(pins) $emu_step(emu_handle, pins)
`endif
`endif

/* The testbench's controls, called hierarchically: u_emu.set_position(0, p) */

// Device `device` (0 for a single encoder, chain position for BiSS) stores
// `position` at its next latch; the testbench owns the position from now on.
task set_position(input integer device, input [63:0] position);
    integer r;
    begin
`ifdef VERILATOR
        r = emu_set_position(emu_handle, device, position);
`else
        r = $emu_set_position(emu_handle, device, position);
`endif
        if (r < 0) emu_fail("set_position");
    end
endtask

// One status bit (`"error"`, `"warning"`, ...) from the next transaction on.
task set_status(input integer device, input `EMU_STR name, input integer value);
    integer r;
    begin
`ifdef VERILATOR
        r = emu_set_status(emu_handle, device, name, value);
`else
        r = $emu_set_status(emu_handle, device, name, value);
`endif
        if (r < 0) emu_fail("set_status");
    end
endtask

// A motion profile from now on (cosim/src/motion.rs), e.g.
// "[motion]\nkind = \"constant\"\nstart = 0\ncounts_per_ms = 500".
task set_motion(input integer device, input `EMU_STR toml);
    integer r;
    begin
`ifdef VERILATOR
        r = emu_set_motion(emu_handle, device, toml);
`else
        r = $emu_set_motion(emu_handle, device, toml);
`endif
        if (r < 0) emu_fail("set_motion");
    end
endtask

// Faults in the scenario's own TOML tables, e.g. "fault = { level = false, from_read = 3 }".
task schedule_fault(input `EMU_STR toml);
    integer r;
    begin
`ifdef VERILATOR
        r = emu_schedule_fault(emu_handle, toml);
`else
        r = $emu_schedule_fault(emu_handle, toml);
`endif
        if (r < 0) emu_fail("schedule_fault");
    end
endtask

// Transactions (latches) so far.
function [63:0] count(input integer unused);
    begin
`ifdef VERILATOR
        count = emu_count(emu_handle);
`else
        count = {$emu_count(emu_handle, 1), $emu_count(emu_handle, 0)};
`endif
    end
endfunction

// The position device `device` latched in the last transaction.
function [63:0] last_value(input integer device);
    begin
`ifdef VERILATOR
        last_value = emu_last_value(emu_handle, device);
`else
        last_value = {$emu_last_value(emu_handle, device, 1), $emu_last_value(emu_handle, device, 0)};
`endif
    end
endfunction

// A status bit device `device` sent in the last transaction (-1: none).
function integer last_status(input integer device, input `EMU_STR name);
    begin
`ifdef VERILATOR
        last_status = emu_last_status(emu_handle, device, name);
`else
        last_status = $emu_last_status(emu_handle, device, name);
`endif
    end
endfunction

// Protocol violations of the master the emulator has seen so far.
function integer violations(input integer unused);
`ifdef VERILATOR
    longint seen;
`endif
    begin
`ifdef VERILATOR
        // Saturates at the largest integer rather than wrapping negative.
        seen = emu_violations(emu_handle);
        violations = (seen > 64'sd2147483647) ? 2147483647 : seen[31:0];
`else
        violations = $emu_violations(emu_handle);
`endif
    end
endfunction

// Prints the violations not yet shown (each with its time and the seed's
// rule); stops the run when `stop` is set.
task emu_show_violations(input integer stop);
    integer n;
`ifdef VERILATOR
    string line;
`endif
    begin
`ifdef VERILATOR
        n = 0;
        line = emu_take_violation(emu_handle);
        while (line != "") begin
            $display("PROTOCOL VIOLATION by the master on %m %0s", line);
            n = n + 1;
            line = emu_take_violation(emu_handle);
        end
`else
        n = $emu_print_violations(emu_handle, "");
`endif
        if (stop != 0 && n > 0)
            $fatal(1, "the master broke a timing rule of the protocol (STOP_ON_VIOLATION = 1)");
    end
endtask

// Opens the emulator at time 0; a bad configuration stops the run here.
// Under DPI-C the transcript is written by the wrapper's `final` block, so
// the task leaves its last argument unused there (lint waiver below).
/* verilator lint_off UNUSEDSIGNAL */
task emu_start(input `EMU_STR kind, input `EMU_STR path, input [63:0] f_emu_hz, input `EMU_STR transcript);
    begin
`ifdef VERILATOR
        emu_handle = emu_open(kind, path, f_emu_hz);
`else
        emu_handle = $emu_open(kind, path, f_emu_hz, transcript);
`endif
        if (emu_handle < 0) emu_fail("opening the emulator");
    end
endtask
/* verilator lint_on UNUSEDSIGNAL */
