-- tb_biss_aligned_reader: biss_aligned_reader closed-loop against
-- encoder-tb's BiSS-C slave emulator, with the pin-level monitor beside it,
-- in GHDL. Copy this file, slave.toml and the Makefile next to your own
-- reader, change the instance, and run `make`.
--
-- Each frame: a random position and random error and warning bits go into
-- the emulator, the reader is asked, and what it read (position, nE, nW,
-- its CRC check) must equal what the emulator says it sent, and (once the
-- frame has ended) what the monitor decoded; no timing rule may be broken.
-- FLIP_BIT >= 0 flips that bit of the reader's position at frame FLIP_READ:
-- a planted misread the bench must catch (make FLIP_BIT=3 must fail).

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

library work;
use work.emu_pkg.all;
use work.emu_random_pkg.all;

entity tb_biss_aligned_reader is
    generic (
        READS : positive := 1000;
        FLIP_BIT : integer := -1;
        FLIP_READ : natural := 500
    );
end entity;

architecture bench of tb_biss_aligned_reader is
    constant BITS : positive := 18;
    constant PERIOD : time := 12.5 ns;     -- 80 MHz: the reader's, the emulator's and the monitor's clock
    signal clk : std_logic := '0';
    signal arst : std_logic := '1';
    signal req, busy, valid, err_n, warn_n, crc_ok, ma, slo : std_logic;
    signal data : unsigned(BITS - 1 downto 0);
begin
    clk <= not clk after PERIOD / 2;

    dut : entity work.biss_aligned_reader
        generic map (DATA_BITS => BITS, HALF => 16)     -- MA 2.5 MHz
        port map (clk => clk, arst => arst, req => req, busy => busy, valid => valid, data => data,
                  err_n => err_n, warn_n => warn_n, crc_ok => crc_ok, ma => ma, slo => slo);

    u_emu : entity work.biss_slave_emu
        generic map (CONFIG => "slave.toml", F_EMU_HZ => 80000000, TRANSCRIPT => "build/transcript.json")
        port map (i_emu_clk => clk, i_ma => ma, o_slo => slo);

    -- The pin-level monitor and protocol checker: it only listens.
    u_mon : entity work.biss_monitor
        generic map (CONFIG => "slave.toml", F_MON_HZ => 80000000, TRANSCRIPT => "build/monitor.json")
        port map (i_mon_clk => clk, i_ma => ma, i_slo => slo);

    -- The stimulus drives and samples on the falling edge, the reader and the
    -- emulator work on the rising one: no race between them.
    stimulus : process
        variable rng : emu_random_t;
        variable set, got, sent : unsigned(BITS - 1 downto 0);
        variable error, warning : integer;
    begin
        rng.seed(7);
        req <= '0';
        for i in 1 to 3 loop
            wait until falling_edge(clk);
        end loop;
        arst <= '0';
        for n in 0 to READS - 1 loop
            set := resize(rng.random32, BITS);
            error := to_integer(rng.random32(0 downto 0));
            warning := to_integer(rng.random32(0 downto 0));
            set_position("u_emu", 0, resize(set, 64));
            set_status("u_emu", 0, "error", error);
            set_status("u_emu", 0, "warning", warning);
            req <= '1';
            wait until falling_edge(clk);
            req <= '0';
            wait until falling_edge(clk) and valid = '1';
            got := data;
            if n = FLIP_READ and FLIP_BIT >= 0 then
                got(FLIP_BIT) := not got(FLIP_BIT);
            end if;
            sent := resize(last_value("u_emu", 0), BITS);
            assert got = sent and got = set and crc_ok = '1'
                   and (err_n = '0') = (error = 1) and (warn_n = '0') = (warning = 1)
                report "read " & integer'image(n) & ": reader " & to_hstring(got) & " nE " & std_logic'image(err_n)
                       & " nW " & std_logic'image(warn_n) & " crc_ok " & std_logic'image(crc_ok) & "; emulator sent "
                       & to_hstring(sent) & " error " & integer'image(error) & " warning " & integer'image(warning)
                severity failure;
            wait until falling_edge(clk) and busy = '0';
            assert count("u_mon") = n + 1 and resize(last_value("u_mon", 0), BITS) = got
                   and last_status("u_mon", 0, "crc_ok") = 1
                report "read " & integer'image(n) & ": the monitor decoded " & integer'image(count("u_mon"))
                       & " frames, the last position " & to_hstring(last_value("u_mon", 0)) & "; the reader read "
                       & to_hstring(got) severity failure;
        end loop;
        assert violations("u_emu") = 0 and violations("u_mon") = 0
            report "the reader broke " & integer'image(violations("u_emu")) & " + " & integer'image(violations("u_mon"))
                   & " timing rule(s) of BiSS-C (PROTOCOL VIOLATION lines above)" severity failure;
        report "PASS biss_aligned_reader: " & integer'image(READS)
               & " frames equal to what the emulator sent and the monitor decoded, "
               & integer'image(now / PERIOD) & " cycles";
        std.env.finish;
    end process;
end architecture;
