-- tb_ssi_gray_reader: ssi_gray_reader closed-loop against encoder-tb's SSI
-- encoder emulator, with the pin-level monitor beside it, in GHDL. Copy
-- this file, encoder.toml and the Makefile next to your own reader, change
-- the instance, and run `make`.
--
-- Each read: a random position goes into the emulator, the reader is asked,
-- and its value must equal what the emulator says it stored and sent, and
-- (at the next read, once the monitor has seen the read end) what the
-- monitor decoded on the line; no timing rule may be broken. FLIP_BIT >= 0
-- flips that bit of the reader's value at read FLIP_READ: a planted misread
-- the bench must catch (make FLIP_BIT=3 must fail).

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

library work;
use work.emu_pkg.all;
use work.emu_random_pkg.all;

entity tb_ssi_gray_reader is
    generic (
        READS : positive := 1000;
        FLIP_BIT : integer := -1;
        FLIP_READ : natural := 500
    );
end entity;

architecture bench of tb_ssi_gray_reader is
    constant BITS : positive := 13;
    constant PERIOD : time := 125 ns;      -- 8 MHz: the reader's and the emulator's clock
    signal clk : std_logic := '0';
    signal rst : std_logic := '1';
    signal start, busy, ready, ssi_clk, ssi_data : std_logic;
    signal position : unsigned(BITS - 1 downto 0);
begin
    clk <= not clk after PERIOD / 2;

    dut : entity work.ssi_gray_reader
        generic map (BITS => BITS, HALF => 20, T_CS => 44, REST => 280)   -- 200 kHz, T_cs 5.5 us, 35 us rest
        port map (clk => clk, rst => rst, start => start, busy => busy, ready => ready,
                  position => position, ssi_clk => ssi_clk, ssi_data => ssi_data);

    u_emu : entity work.ssi_encoder_emu
        generic map (CONFIG => "encoder.toml", F_EMU_HZ => 8000000, TRANSCRIPT => "build/transcript.json")
        port map (i_emu_clk => clk, i_ssi_clk => ssi_clk, o_ssi_data => ssi_data);

    -- The pin-level monitor and protocol checker: it only listens.
    u_mon : entity work.ssi_monitor
        generic map (CONFIG => "encoder.toml", F_MON_HZ => 8000000, TRANSCRIPT => "build/monitor.json")
        port map (i_mon_clk => clk, i_ssi_clk => ssi_clk, i_ssi_data => ssi_data);

    -- The stimulus drives and samples on the falling edge, the reader and the
    -- emulator work on the rising one: no race between them.
    stimulus : process
        variable rng : emu_random_t;
        variable set, got, sent : unsigned(BITS - 1 downto 0);
    begin
        rng.seed(7);
        start <= '0';
        for i in 1 to 3 loop
            wait until falling_edge(clk);
        end loop;
        rst <= '0';
        for n in 0 to READS - 1 loop
            set := resize(rng.random32, BITS);
            set_position("u_emu", 0, resize(set, 64));
            start <= '1';
            wait until falling_edge(clk);
            start <= '0';
            wait until falling_edge(clk) and ready = '1';
            got := position;
            if n = FLIP_READ and FLIP_BIT >= 0 then
                got(FLIP_BIT) := not got(FLIP_BIT);
            end if;
            sent := resize(last_value("u_emu", 0), BITS);
            assert got = sent and got = set
                report "read " & integer'image(n) & ": reader " & to_hstring(got) & ", emulator sent "
                       & to_hstring(sent) & " (set " & to_hstring(set) & ")" severity failure;
            wait until falling_edge(clk) and busy = '0';
            assert count("u_mon") = n + 1 and resize(last_value("u_mon", 0), BITS) = got
                report "read " & integer'image(n) & ": the monitor decoded " & integer'image(count("u_mon"))
                       & " reads, the last position " & to_hstring(last_value("u_mon", 0)) & "; the reader read "
                       & to_hstring(got) severity failure;
        end loop;
        assert violations("u_emu") = 0 and violations("u_mon") = 0
            report "the reader broke " & integer'image(violations("u_emu")) & " + " & integer'image(violations("u_mon"))
                   & " timing rule(s) of SSI (PROTOCOL VIOLATION lines above)" severity failure;
        report "PASS ssi_gray_reader: " & integer'image(READS) & " reads equal to what the emulator sent and the monitor decoded, "
               & integer'image(now / PERIOD) & " cycles";
        std.env.finish;
    end process;
end architecture;
