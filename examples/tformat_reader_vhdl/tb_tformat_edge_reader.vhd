-- tb_tformat_edge_reader: tformat_edge_reader closed-loop against
-- encoder-tb's T-format encoder emulator, with the pin-level monitor beside
-- it, in GHDL. Copy this file, encoder.toml and the Makefile next to your
-- own reader, change the instance, and run `make`.
--
-- Each read: a random position (ABM << 17 | ABS) goes into the emulator,
-- the reader asks for ABS (Data ID 0) or ABM (Data ID 1, every third read),
-- and what it read must equal what the emulator says it sent, and (once the
-- answer has ended) what the monitor decoded (both hold the field a Data ID
-- does not carry); no timing rule may be broken. FLIP_BIT >= 0 flips that
-- bit of the reader's ABS at read FLIP_READ: a planted misread the bench
-- must catch (make FLIP_BIT=3 must fail).

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

library work;
use work.emu_pkg.all;
use work.emu_random_pkg.all;

entity tb_tformat_edge_reader is
    generic (
        READS : positive := 1000;
        FLIP_BIT : integer := -1;
        FLIP_READ : natural := 500
    );
end entity;

architecture bench of tb_tformat_edge_reader is
    constant PERIOD : time := 25 ns;       -- 40 MHz: the reader's, the emulator's and the monitor's clock
    signal clk : std_logic := '0';
    signal rst_n : std_logic := '0';
    signal request, data_id, busy, valid, fail, de, tx, rx, encoder_oe : std_logic;
    signal abs_pos : unsigned(16 downto 0);
    signal abm_pos : unsigned(15 downto 0);
    signal sf : std_logic_vector(7 downto 0);
begin
    clk <= not clk after PERIOD / 2;

    dut : entity work.tformat_edge_reader
        generic map (BIT_CLOCKS => 16, TIMEOUT => 800)     -- 2.5 Mbps, 20 us timeout
        port map (clk => clk, rst_n => rst_n, request => request, data_id => data_id, busy => busy,
                  valid => valid, fail => fail, abs_pos => abs_pos, abm_pos => abm_pos, sf => sf,
                  de => de, tx => tx, rx => rx);

    u_emu : entity work.tformat_encoder_emu
        generic map (CONFIG => "encoder.toml", F_EMU_HZ => 40000000, TRANSCRIPT => "build/transcript.json")
        port map (i_emu_clk => clk, i_tf_data => tx, i_tf_data_oe => de, o_tf_data => rx, o_tf_data_oe => encoder_oe);

    -- The pin-level monitor and protocol checker: it only listens.
    u_mon : entity work.tformat_monitor
        generic map (CONFIG => "encoder.toml", F_MON_HZ => 40000000, TRANSCRIPT => "build/monitor.json")
        port map (i_mon_clk => clk, i_tf_data => tx, i_tf_data_oe => de, i_tf_rx => rx);

    -- The stimulus drives and samples on the falling edge, the reader and the
    -- emulator work on the rising one: no race between them.
    stimulus : process
        variable rng : emu_random_t;
        variable set_abs, got_abs : unsigned(16 downto 0);
        variable set_abm, got_abm : unsigned(15 downto 0);
        variable sent : unsigned(63 downto 0);
        variable want : unsigned(32 downto 0);
        variable abm_read : boolean := false;
    begin
        rng.seed(17);
        request <= '0';
        data_id <= '0';
        for i in 1 to 3 loop
            wait until falling_edge(clk);
        end loop;
        rst_n <= '1';
        for n in 0 to READS - 1 loop
            set_abs := resize(rng.random32, 17);
            set_abm := resize(rng.random32, 16);
            set_position("u_emu", 0, resize(set_abm & set_abs, 64));
            for i in 1 to 40 loop                  -- 1 us between the answer's end and the next request
                wait until falling_edge(clk);
            end loop;
            if n mod 3 = 0 then data_id <= '1'; else data_id <= '0'; end if;
            request <= '1';
            wait until falling_edge(clk);
            request <= '0';
            wait until falling_edge(clk) and (valid = '1' or fail = '1');
            got_abs := abs_pos;
            got_abm := abm_pos;
            if n = FLIP_READ and FLIP_BIT >= 0 then
                got_abs(FLIP_BIT) := not got_abs(FLIP_BIT);
            end if;
            sent := last_value("u_emu", 0);
            -- last_value: ABM << 17 for Data ID 1, ABS alone for Data ID 0.
            if data_id = '1' then
                abm_read := true;
                assert fail = '0' and got_abm = set_abm and sent = resize(set_abm & "00000000000000000", 64)
                    report "read " & integer'image(n) & " (Data ID 1): reader ABM " & to_hstring(got_abm) & " fail "
                           & std_logic'image(fail) & "; emulator sent " & to_hstring(sent) & " (set ABM "
                           & to_hstring(set_abm) & ")" severity failure;
            else
                assert fail = '0' and got_abs = set_abs and sent = resize(set_abs, 64)
                    report "read " & integer'image(n) & " (Data ID 0): reader ABS " & to_hstring(got_abs) & " fail "
                           & std_logic'image(fail) & "; emulator sent " & to_hstring(sent) & " (set ABS "
                           & to_hstring(set_abs) & ")" severity failure;
            end if;
            wait until falling_edge(clk) and busy = '0';
            want := got_abm & got_abs;
            assert count("u_mon") = n + 1 and (n = 0 or resize(last_value("u_mon", 0), 33) = want)
                report "read " & integer'image(n) & ": the monitor decoded " & integer'image(count("u_mon"))
                       & " readouts, the last ABM << 17 | ABS " & to_hstring(last_value("u_mon", 0))
                       & "; the reader holds " & to_hstring(want) severity failure;
        end loop;
        assert violations("u_emu") = 0 and violations("u_mon") = 0
            report "the reader broke " & integer'image(violations("u_emu")) & " + " & integer'image(violations("u_mon"))
                   & " timing rule(s) of T-format (PROTOCOL VIOLATION lines above)" severity failure;
        report "PASS tformat_edge_reader: " & integer'image(READS)
               & " reads equal to what the emulator sent and the monitor decoded, "
               & integer'image(now / PERIOD) & " cycles";
        std.env.finish;
    end process;
end architecture;
