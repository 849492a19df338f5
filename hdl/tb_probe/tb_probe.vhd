-- tb_probe: hdl/tb_probe/tb_probe.v in VHDL, for GHDL: replays one rule
-- probe (`tbgen probes --out DIR`) into a protocol's VHDL emulator and
-- monitor (hdl/emu/vhdl/), wired by the kit's generated entity
-- DIR/<kind>/probe_wiring.vhd, and leaves their transcripts for `tbgen
-- probes --check DIR --sim ghdl`. Run in a probe's folder's ghdl/
-- subfolder; it reads ../stimulus.mem and ../monitor.mem (tb_probe.v says
-- what they hold) and writes emulator.json and monitor.json (at exit).
-- Timing as there: both wrappers sample on each rising edge; the master's
-- pins for the next cycle change with the edge; an unknown pin is 'X'.
library ieee;
use ieee.std_logic_1164.all;
use std.textio.all;

entity tb_probe is
    generic (F_HZ : natural := 200000000);
end entity;

architecture bench of tb_probe is
    -- The half period only spaces the edges: the wrappers count cycles at F_HZ.
    constant HALF : time := (1 sec / F_HZ) / 2;
    signal clk : std_logic := '0';
    signal master : std_logic_vector(15 downto 0) := (others => '1');
    signal answer : std_logic_vector(3 downto 0);
    signal mon_pins : std_logic_vector(7 downto 0);
    type table_t is array (0 to 7) of std_logic_vector(7 downto 0);

    impure function read_table return table_t is
        file f : text open read_mode is "../monitor.mem";
        variable l : line;
        variable t : table_t := (others => x"ff");
        variable k : natural := 0;
    begin
        while not endfile(f) and k < 8 loop
            readline(f, l);
            hread(l, t(k));
            k := k + 1;
        end loop;
        return t;
    end function;
    constant SOURCES : table_t := read_table;

    -- One monitor pin from its source (the byte tbgen probes writes): a
    -- master pin, an emulator pin, the half-duplex bus at the master's
    -- receiver, or the wired-AND CAN bus; in the last two an unknown master
    -- pin reads as 0, as the library's run reads it.
    function src_level(s : std_logic_vector(7 downto 0); m : std_logic_vector(15 downto 0);
                       a : std_logic_vector(3 downto 0)) return std_logic is
        variable pin : natural := 0;
    begin
        for k in 3 downto 0 loop
            pin := pin * 2;
            if s(k) = '1' then
                pin := pin + 1;
            end if;
        end loop;
        case s(7 downto 4) is
            when x"0" => return m(pin);
            when x"1" => return a(pin mod 4);
            when x"2" =>
                if a(1) = '1' then return a(0); elsif m(2) = '1' then return m(1); else return '1'; end if;
            when x"3" =>
                if m(pin) = '1' then return a(0); else return '0'; end if;
            when others => return 'X';
        end case;
    end function;
begin
    clk <= not clk after HALF;

    pins : for i in 0 to 7 generate
        mon_pins(i) <= src_level(SOURCES(i), master, answer);
    end generate;

    u_wiring : entity work.probe_wiring
        generic map (F_HZ => F_HZ)
        port map (clk => clk, master => master, answer => answer, mon_pins => mon_pins);

    stimulus : process
        file f : text open read_mode is "../stimulus.mem";
        variable l : line;
        variable w : std_logic_vector(63 downto 0);
        variable left : natural;
        variable levels : std_logic_vector(15 downto 0);
    begin
        loop
            exit when endfile(f);
            readline(f, l);
            hread(l, w);
            exit when w(63 downto 32) = x"00000000";
            levels := w(15 downto 0);
            for k in 0 to 15 loop
                if w(16 + k) = '1' then
                    levels(k) := 'X';
                end if;
            end loop;
            master <= levels;
            left := 0;
            for k in 63 downto 32 loop
                left := left * 2;
                if w(k) = '1' then
                    left := left + 1;
                end if;
            end loop;
            for c in 1 to left loop
                wait until rising_edge(clk);
            end loop;
        end loop;
        wait until falling_edge(clk);
        std.env.finish;
    end process;
end architecture;
