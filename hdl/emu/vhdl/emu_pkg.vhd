-- emu_pkg: the testbench's controls of the VHDL emulators and monitors
-- (hdl/emu/vhdl/<name>.vhd), and what their bodies share, over the emulator
-- library's C ABI (emu_ffi).
--
-- A VHDL testbench cannot call into an instance as a Verilog one does
-- (u_emu.set_position(0, p)), so each emulator and monitor registers its
-- handle under its path name when it is elaborated, and a control names the
-- instance: its label, or any tail of its path ("u_emu", "u_dut:u_emu"):
--
--   set_position("u_emu", 0, to_unsigned(p, 64));   -- before a read
--   assert last_value("u_emu", 0) = resize(my_value, 64) report "misread" severity failure;
--   count("u_emu"), violations("u_mon"), last_status("u_mon", 0, "crc_ok") ...
--
-- The calls are those of hdl/emu/emu_api.vh with the instance first; each
-- argument and result is as there (cosim/src/ffi.rs). A failure (an
-- unknown name, a bad status or fault table) stops the run with the
-- library's message.

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use std.textio.all;

use work.emu_ffi.all;

package emu_pkg is

    subtype int64 is emu_int64;

    /* Controls of an emulator or monitor, by instance name */
    procedure set_position(inst : string; device : natural; position : unsigned);
    procedure set_status(inst : string; device : natural; name : string; value : integer);
    procedure set_motion(inst : string; device : natural; toml : string);
    procedure schedule_fault(inst : string; toml : string);
    impure function count(inst : string) return natural;
    impure function last_value(inst : string; device : natural) return unsigned;
    impure function last_status(inst : string; device : natural; name : string) return integer;
    impure function violations(inst : string) return natural;

    /* Conversions (emu_ffi says how values cross) */
    function c_str(s : string) return emu_c_string;
    function from_c(c : emu_c_string) return string;
    function to_int64(u : unsigned) return int64;
    function to_unsigned64(v : int64) return unsigned;

    /* For the wrappers' bodies */
    -- Opens the library's `kind` at elaboration and registers it under
    -- `path` (the instance's 'path_name); the configuration is `config`,
    -- else the plusarg +<plusarg>=<file>; the transcript goes to
    -- `transcript` (else +<transcript_plusarg>=<file>, when that is not "")
    -- at the end of the simulation. A bad file stops the elaboration.
    impure function emu_instance(kind, config, plusarg, transcript, transcript_plusarg : string;
                                 f_hz : natural; path : string) return integer;

    -- Each input pin's last 0/1 level, whether it has been 0 or 1 yet (an
    -- unknown level before is the reset's, and ignored), and whether its
    -- present unknown level has been reported.
    type emu_pins_t is record
        level    : std_ulogic_vector(7 downto 0);
        known    : std_ulogic_vector(7 downto 0);
        reported : std_ulogic_vector(7 downto 0);
        cycle    : int64;
    end record;
    function emu_pins_init(idle : std_ulogic_vector(7 downto 0)) return emu_pins_t;

    -- One rising edge of the emulator's (monitor's) clock: reads `sampled` into
    -- the pins' levels (U, X, Z, W or - on a pin after its first 0/1 is
    -- reported with time and pin and never read as data: `stop_on_x` /= 0
    -- stops the run, else the last level holds; H and L read as 1 and 0),
    -- steps the library once and returns its output pins (bit 0 data, bit 1
    -- driver enable, bit 2 a half-duplex line's resolved level); prints the master's violations (`stop_on_violation`
    -- /= 0 stops the run). `oe_pin` >= 0 names a driver-enable input whose
    -- unknown level reads as 0, the master not driving (one warning), and
    -- `data_pin` the data of that driver, not read while it is unknown.
    -- `names` are the pins' names, comma-separated, pin 0 first.
    procedure emu_clock(handle : integer; path, what, names : string;
                        sampled : std_ulogic_vector(7 downto 0); oe_pin, data_pin : integer;
                        stop_on_x, stop_on_violation : integer;
                        pins : inout emu_pins_t; output : out std_ulogic_vector(2 downto 0));

end package;

package body emu_pkg is

    constant NUL : character := character'val(0);

    function lower(s : string) return string is
        variable r : string(1 to s'length) := s;
    begin
        for i in r'range loop
            if r(i) >= 'A' and r(i) <= 'Z' then
                r(i) := character'val(character'pos(r(i)) + 32);
            end if;
        end loop;
        return r;
    end function;

    function c_str(s : string) return emu_c_string is
        variable r : emu_c_string := (others => NUL);
    begin
        assert s'length < r'length
            report "a string of " & integer'image(s'length) & " characters passed to the emulator library: at most "
                   & integer'image(r'length - 1) & " fit (emu_ffi.emu_c_string)"
            severity failure;
        r(1 to s'length) := s;
        return r;
    end function;

    -- An instance's path without the colon GHDL ends it with.
    function instance_name(path : string) return string is
    begin
        if path'length > 1 and path(path'high) = ':' then
            return path(path'low to path'high - 1);
        end if;
        return path;
    end function;

    function from_c(c : emu_c_string) return string is
    begin
        for i in c'range loop
            if c(i) = NUL then
                return c(1 to i - 1);
            end if;
        end loop;
        return c;
    end function;

    -- Bit by bit, as the two's complement the C ABI carries (an unsigned
    -- of 64 bits with bit 63 set is a negative int64).
    function to_int64(u : unsigned) return int64 is
        variable w : unsigned(63 downto 0) := resize(u, 64);
        variable r : int64 := 0;
    begin
        for i in 62 downto 0 loop
            r := r * 2;
            if w(i) = '1' then
                r := r + 1;
            end if;
        end loop;
        if w(63) = '1' then
            r := r - 4611686018427387904 - 4611686018427387904;
        end if;
        return r;
    end function;

    function to_unsigned64(v : int64) return unsigned is
        variable r : unsigned(63 downto 0);
        variable x : int64 := v;
    begin
        -- mod 2 is 0 or 1 for negative x too, and (x - x mod 2) / 2 is exact.
        for i in 0 to 63 loop
            if x mod 2 = 1 then
                r(i) := '1';
            else
                r(i) := '0';
            end if;
            x := (x - x mod 2) / 2;
        end loop;
        return r;
    end function;

    impure function last_error return string is
        variable buf : emu_c_string;
        variable n : integer;
    begin
        emu_last_error_copy(buf, buf'length, n);
        return from_c(buf);
    end function;

    /* The instances, by path name */

    type registry_t is protected
        procedure add(path : string; handle : integer);
        impure function find(inst : string) return integer;
    end protected;

    type registry_t is protected body
        constant MAX : natural := 64;
        constant WIDTH : natural := 256;
        type paths_t is array (1 to MAX) of string(1 to WIDTH);
        type ints_t is array (1 to MAX) of integer;
        variable paths : paths_t;
        variable lengths : ints_t;
        variable handles : ints_t;
        variable used : natural := 0;

        procedure add(path : string; handle : integer) is
        begin
            assert used < MAX and path'length <= WIDTH
                report "emu_pkg: more than " & integer'image(MAX) & " emulators and monitors, or a path longer than "
                       & integer'image(WIDTH) & " characters: " & path
                severity failure;
            used := used + 1;
            paths(used)(1 to path'length) := path;
            lengths(used) := path'length;
            handles(used) := handle;
        end procedure;

        -- The one instance whose path ends in ":<inst>:" (GHDL writes
        -- paths in lower case, a name may be given in any).
        impure function find(inst : string) return integer is
            constant tail : string := ":" & lower(inst) & ":";
            variable found : integer := 0;
            variable all_paths : line;
        begin
            for i in 1 to used loop
                if lengths(i) >= tail'length
                   and paths(i)(lengths(i) - tail'length + 1 to lengths(i)) = tail then
                    assert found = 0
                        report "emu_pkg: two instances end in " & tail & ": " & paths(found)(1 to lengths(found))
                               & " and " & paths(i)(1 to lengths(i)) & "; name one by more of its path (""u_top:u_emu"")"
                        severity failure;
                    found := i;
                end if;
            end loop;
            if found = 0 then
                write(all_paths, string'("none"));
                if used > 0 then
                    deallocate(all_paths);
                    for i in 1 to used loop
                        write(all_paths, paths(i)(1 to lengths(i)) & " ");
                    end loop;
                end if;
                report "emu_pkg: no emulator or monitor instance is named " & inst & " (instances: "
                       & all_paths.all & "); give its label" severity failure;
                return -1;
            end if;
            return handles(found);
        end function;
    end protected body;

    shared variable registry : registry_t;

    impure function handle_of(inst : string) return integer is
    begin
        return registry.find(inst);
    end function;

    procedure check(r : integer; what, inst : string) is
    begin
        assert r >= 0 report what & " on " & inst & ": " & last_error severity failure;
    end procedure;

    procedure set_position(inst : string; device : natural; position : unsigned) is
    begin
        check(emu_set_position(handle_of(inst), device, to_int64(position)), "set_position", inst);
    end procedure;

    procedure set_status(inst : string; device : natural; name : string; value : integer) is
    begin
        check(emu_set_status(handle_of(inst), device, c_str(name), value), "set_status", inst);
    end procedure;

    procedure set_motion(inst : string; device : natural; toml : string) is
    begin
        check(emu_set_motion(handle_of(inst), device, c_str(toml)), "set_motion", inst);
    end procedure;

    procedure schedule_fault(inst : string; toml : string) is
    begin
        check(emu_schedule_fault(handle_of(inst), c_str(toml)), "schedule_fault", inst);
    end procedure;

    impure function count(inst : string) return natural is
        constant n : int64 := emu_count(handle_of(inst));
    begin
        assert n >= 0 report "count on " & inst & ": " & last_error severity failure;
        if n > int64(natural'high) then
            return natural'high;
        end if;
        return natural(n);
    end function;

    impure function last_value(inst : string; device : natural) return unsigned is
    begin
        return to_unsigned64(emu_last_value(handle_of(inst), device));
    end function;

    impure function last_status(inst : string; device : natural; name : string) return integer is
    begin
        return emu_last_status(handle_of(inst), device, c_str(name));
    end function;

    impure function violations(inst : string) return natural is
        constant n : int64 := emu_violations(handle_of(inst));
    begin
        assert n >= 0 report "violations on " & inst & ": " & last_error severity failure;
        if n > int64(natural'high) then
            return natural'high;
        end if;
        return natural(n);
    end function;

    impure function plusarg_value(name : string) return string is
        variable buf : emu_c_string;
        variable n : integer;
    begin
        emu_plusarg(c_str(name), buf, buf'length, n);
        if n < 0 then
            return "";
        end if;
        return from_c(buf);
    end function;

    impure function emu_instance(kind, config, plusarg, transcript, transcript_plusarg : string;
                                 f_hz : natural; path : string) return integer is
        impure function chosen(value, plus : string) return string is
        begin
            if value /= "" or plus = "" then
                return value;
            end if;
            return plusarg_value(plus);
        end function;
        constant config_path : string := chosen(config, plusarg);
        constant transcript_path : string := chosen(transcript, transcript_plusarg);
        variable handle : integer;
    begin
        handle := emu_open(c_str(kind), c_str(config_path), int64(f_hz));
        assert handle > 0
            report "ERROR: " & instance_name(path) & ": opening the " & kind & " emulator library failed: " & last_error
                   & " (the generic CONFIG, or the plusarg +" & plusarg & "=<file>)"
            severity failure;
        if handle > 0 and transcript_path /= "" then
            assert emu_transcript_at_exit(handle, c_str(transcript_path)) = 0
                report instance_name(path) & ": transcript " & transcript_path & ": " & last_error severity failure;
        end if;
        registry.add(path, handle);
        return handle;
    end function;

    function emu_pins_init(idle : std_ulogic_vector(7 downto 0)) return emu_pins_t is
    begin
        return (level => idle, known => (others => '0'), reported => (others => '0'), cycle => 0);
    end function;

    -- The k-th comma-separated name of `names`.
    function pin_name(names : string; k : natural) return string is
        variable first : positive := names'low;
        variable seen : natural := 0;
    begin
        for i in names'range loop
            if names(i) = ',' then
                if seen = k then
                    return names(first to i - 1);
                end if;
                seen := seen + 1;
                first := i + 2;
            end if;
        end loop;
        return names(first to names'high);
    end function;

    procedure show_violations(handle : integer; path : string; stop : integer) is
        variable buf : emu_c_string;
        variable n : integer;
        variable shown : natural := 0;
    begin
        loop
            emu_take_violation_copy(handle, buf, buf'length, n);
            exit when n <= 0;
            report "PROTOCOL VIOLATION by the master on " & instance_name(path) & " " & from_c(buf) severity warning;
            shown := shown + 1;
        end loop;
        assert stop = 0 or shown = 0
            report instance_name(path) & ": the master broke a timing rule of the protocol (STOP_ON_VIOLATION = 1)" severity failure;
    end procedure;

    procedure emu_clock(handle : integer; path, what, names : string;
                        sampled : std_ulogic_vector(7 downto 0); oe_pin, data_pin : integer;
                        stop_on_x, stop_on_violation : integer;
                        pins : inout emu_pins_t; output : out std_ulogic_vector(2 downto 0)) is
        variable v : std_ulogic;
        variable word : integer := 0;
        variable out_word : integer;
        variable oe_unknown : boolean := false;
    begin
        if oe_pin >= 0 then
            oe_unknown := to_x01(sampled(oe_pin)) = 'X';
        end if;
        for k in 0 to 7 loop
            v := to_x01(sampled(k));
            if v /= 'X' then
                pins.level(k) := v;
                pins.known(k) := '1';
                pins.reported(k) := '0';
            elsif k = oe_pin then
                -- The master does not drive (as before its reset): one
                -- warning, never a protocol report.
                pins.level(k) := '0';
                if pins.known(k) = '1' and pins.reported(k) = '0' then
                    report "WARNING: " & instance_name(path) & ": X or Z (" & std_ulogic'image(sampled(k))
                           & ") on the driver enable " & pin_name(names, k) & " at " & to_string(now, ns) & ", " & what
                           & " cycle " & int64'image(pins.cycle) & ": read as 0, the master not driving" severity warning;
                end if;
                pins.reported(k) := '1';
            elsif k = data_pin and oe_unknown then
                -- The data of a driver whose enable is unknown is not read.
                pins.level(k) := '1';
            elsif pins.known(k) = '1' and pins.reported(k) = '0' then
                pins.reported(k) := '1';
                -- The words of the Verilog wrappers' message (tbgen probes
                -- --check counts them), with the value that was seen.
                report "ERROR: " & instance_name(path) & ": X or Z (" & std_ulogic'image(sampled(k)) & ") on "
                       & what & " input " & pin_name(names, k) & " at " & to_string(now, ns) & ", " & what & " cycle "
                       & int64'image(pins.cycle) & " (held at " & std_ulogic'image(pins.level(k)) & ", not read as data)"
                    severity error;
                assert stop_on_x = 0
                    report what & " input " & pin_name(names, k) & " is X or Z (STOP_ON_X = 1)" severity failure;
            end if;
        end loop;
        for k in 7 downto 0 loop
            word := word * 2;
            if pins.level(k) = '1' then
                word := word + 1;
            end if;
        end loop;
        out_word := emu_step(handle, word);
        assert out_word >= 0 report "ERROR: " & instance_name(path) & ": step: " & last_error severity failure;
        pins.cycle := pins.cycle + 1;
        if (out_word / 128) mod 2 = 1 then
            show_violations(handle, path, stop_on_violation);
        end if;
        if out_word mod 2 = 1 then output(0) := '1'; else output(0) := '0'; end if;
        if (out_word / 2) mod 2 = 1 then output(1) := '1'; else output(1) := '0'; end if;
        if (out_word / 4) mod 2 = 1 then output(2) := '1'; else output(2) := '0'; end if;
    end procedure;

end package body;
