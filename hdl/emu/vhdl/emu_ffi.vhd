-- emu_ffi: the emulator library's C ABI (cosim/src/ffi.rs, libcosim.so) as
-- VHDL foreign subprograms (GHDL's VHPIDIRECT), called directly: no C shim.
--
-- How values cross (the one place this is written down):
--   int32_t      integer (GHDL's integer is 32 bits), by value.
--   int64_t      emu_int64, a 64-bit integer type, by value; a 64-bit
--                position travels as its two's complement (emu_pkg's
--                to_int64 / to_unsigned64 convert from and to unsigned).
--   const char * emu_c_string, string(1 to 1024): a constrained array is
--                passed as a pointer to its first character; emu_pkg's
--                c_str pads a VHDL string with NULs, which ends it for C
--                (and the library trims them).
--   char *buf    the same type as an `out` parameter: the library copies
--                a NUL-terminated text into it (VHDL cannot read a returned
--                pointer), emu_pkg's from_c reads it. Such calls are
--                procedures (a VHDL-2008 function has no `out` parameter)
--                with the C function's result in `result : out integer`,
--                passed by address as every scalar `out` is.
--   the library  "VHPIDIRECT libcosim.so <function>": dlopen finds
--                libcosim.so on LD_LIBRARY_PATH, which must name its
--                directory when GHDL analyses this file (the mcode backend
--                loads the library then) and when the simulation runs
--                (hdl/emu/emu.mk's RUN_ENV; scripts/emu_lib.sh prints the
--                directory as EMU_LIB_DIR). GHDL's llvm and gcc backends
--                ignore the name and link instead: -Wl,-L<dir> -Wl,-lcosim.
--   NVC: docs/cosim.md, "VHDL in GHDL".
--
-- Each function's contract (return values, errors) is its comment in
-- cosim/src/ffi.rs. The bodies below only run when the binding failed.

package emu_ffi is

    type emu_int64 is range -9223372036854775807 - 1 to 9223372036854775807;
    subtype emu_c_string is string(1 to 1024);

    impure function emu_open(kind : emu_c_string; path : emu_c_string; f_emu_hz : emu_int64) return integer;
    attribute foreign of emu_open : function is "VHPIDIRECT libcosim.so emu_open";
    impure function emu_step(handle : integer; pins : integer) return integer;
    attribute foreign of emu_step : function is "VHPIDIRECT libcosim.so emu_step";
    impure function emu_set_position(handle : integer; device : integer; position : emu_int64) return integer;
    attribute foreign of emu_set_position : function is "VHPIDIRECT libcosim.so emu_set_position";
    impure function emu_set_status(handle : integer; device : integer; name : emu_c_string; value : integer) return integer;
    attribute foreign of emu_set_status : function is "VHPIDIRECT libcosim.so emu_set_status";
    impure function emu_set_motion(handle : integer; device : integer; toml : emu_c_string) return integer;
    attribute foreign of emu_set_motion : function is "VHPIDIRECT libcosim.so emu_set_motion";
    impure function emu_schedule_fault(handle : integer; toml : emu_c_string) return integer;
    attribute foreign of emu_schedule_fault : function is "VHPIDIRECT libcosim.so emu_schedule_fault";
    impure function emu_count(handle : integer) return emu_int64;
    attribute foreign of emu_count : function is "VHPIDIRECT libcosim.so emu_count";
    impure function emu_last_value(handle : integer; device : integer) return emu_int64;
    attribute foreign of emu_last_value : function is "VHPIDIRECT libcosim.so emu_last_value";
    impure function emu_last_status(handle : integer; device : integer; name : emu_c_string) return integer;
    attribute foreign of emu_last_status : function is "VHPIDIRECT libcosim.so emu_last_status";
    impure function emu_violations(handle : integer) return emu_int64;
    attribute foreign of emu_violations : function is "VHPIDIRECT libcosim.so emu_violations";
    procedure emu_take_violation_copy(handle : integer; buf : out emu_c_string; len : integer; result : out integer);
    attribute foreign of emu_take_violation_copy : procedure is "VHPIDIRECT libcosim.so emu_take_violation_copy";
    procedure emu_last_error_copy(buf : out emu_c_string; len : integer; result : out integer);
    attribute foreign of emu_last_error_copy : procedure is "VHPIDIRECT libcosim.so emu_last_error_copy";
    procedure emu_plusarg(name : emu_c_string; buf : out emu_c_string; len : integer; result : out integer);
    attribute foreign of emu_plusarg : procedure is "VHPIDIRECT libcosim.so emu_plusarg";
    impure function emu_transcript_at_exit(handle : integer; path : emu_c_string) return integer;
    attribute foreign of emu_transcript_at_exit : function is "VHPIDIRECT libcosim.so emu_transcript_at_exit";

end package;

package body emu_ffi is

    constant NOT_BOUND : string := " is not bound to libcosim.so: analyse emu_ffi.vhd with GHDL and LD_LIBRARY_PATH naming the library's directory";

    impure function emu_open(kind : emu_c_string; path : emu_c_string; f_emu_hz : emu_int64) return integer is
    begin
        report "emu_open" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_step(handle : integer; pins : integer) return integer is
    begin
        report "emu_step" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_set_position(handle : integer; device : integer; position : emu_int64) return integer is
    begin
        report "emu_set_position" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_set_status(handle : integer; device : integer; name : emu_c_string; value : integer) return integer is
    begin
        report "emu_set_status" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_set_motion(handle : integer; device : integer; toml : emu_c_string) return integer is
    begin
        report "emu_set_motion" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_schedule_fault(handle : integer; toml : emu_c_string) return integer is
    begin
        report "emu_schedule_fault" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_count(handle : integer) return emu_int64 is
    begin
        report "emu_count" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_last_value(handle : integer; device : integer) return emu_int64 is
    begin
        report "emu_last_value" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_last_status(handle : integer; device : integer; name : emu_c_string) return integer is
    begin
        report "emu_last_status" & NOT_BOUND severity failure;
        return -1;
    end function;
    impure function emu_violations(handle : integer) return emu_int64 is
    begin
        report "emu_violations" & NOT_BOUND severity failure;
        return -1;
    end function;
    procedure emu_take_violation_copy(handle : integer; buf : out emu_c_string; len : integer; result : out integer) is
    begin
        report "emu_take_violation_copy" & NOT_BOUND severity failure;
        result := -1;
    end procedure;
    procedure emu_last_error_copy(buf : out emu_c_string; len : integer; result : out integer) is
    begin
        report "emu_last_error_copy" & NOT_BOUND severity failure;
        result := -1;
    end procedure;
    procedure emu_plusarg(name : emu_c_string; buf : out emu_c_string; len : integer; result : out integer) is
    begin
        report "emu_plusarg" & NOT_BOUND severity failure;
        result := -1;
    end procedure;
    impure function emu_transcript_at_exit(handle : integer; path : emu_c_string) return integer is
    begin
        report "emu_transcript_at_exit" & NOT_BOUND severity failure;
        return -1;
    end function;

end package body;
