-- tb_endat22_reader: endat22_reader closed-loop against encoder-tb's EnDat
-- encoder emulator, with the pin-level monitor beside it, in GHDL. Copy
-- this file, encoder.toml and the Makefile next to your own reader, change
-- the instance, and run `make`.
--
-- Each read: a random position and random F1 and F2 go into the emulator,
-- the reader is asked, and what it read (position, F1, F2, its CRC check)
-- must equal what the emulator says it sent, and (once the transfer has
-- ended) what the monitor decoded; no timing rule may be broken. FLIP_BIT
-- >= 0 flips that bit of the reader's position at read FLIP_READ: a planted
-- misread the bench must catch (make FLIP_BIT=3 must fail).

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

library work;
use work.emu_pkg.all;
use work.emu_random_pkg.all;

entity tb_endat22_reader is
    generic (
        READS : positive := 1000;
        FLIP_BIT : integer := -1;
        FLIP_READ : natural := 500
    );
end entity;

architecture bench of tb_endat22_reader is
    constant BITS : positive := 21;
    constant PERIOD : time := 62.5 ns;     -- 16 MHz: the reader's, the emulator's and the monitor's clock
    signal clk : std_logic := '0';
    signal rst_n : std_logic := '0';
    signal read_pos, busy, done, f1, f2, crc_good, timeout : std_logic;
    signal endat_clk, endat_de, endat_do, endat_di, encoder_oe : std_logic;
    signal pos : unsigned(BITS - 1 downto 0);
begin
    clk <= not clk after PERIOD / 2;

    dut : entity work.endat22_reader
        generic map (POS_BITS => BITS, HALF => 16, SAMPLE => 13)     -- 500 kHz
        port map (clk => clk, rst_n => rst_n, read_pos => read_pos, busy => busy, done => done, pos => pos,
                  f1 => f1, f2 => f2, crc_good => crc_good, timeout => timeout, endat_clk => endat_clk,
                  endat_de => endat_de, endat_do => endat_do, endat_di => endat_di);

    u_emu : entity work.endat_encoder_emu
        generic map (CONFIG => "encoder.toml", F_EMU_HZ => 16000000, TRANSCRIPT => "build/transcript.json")
        port map (i_emu_clk => clk, i_endat_clk => endat_clk, i_endat_data => endat_do, i_endat_data_oe => endat_de,
                  o_endat_data => endat_di, o_endat_data_oe => encoder_oe);

    -- The pin-level monitor and protocol checker: it only listens.
    u_mon : entity work.endat_monitor
        generic map (CONFIG => "encoder.toml", F_MON_HZ => 16000000, TRANSCRIPT => "build/monitor.json")
        port map (i_mon_clk => clk, i_endat_clk => endat_clk, i_endat_data => endat_do,
                  i_endat_data_oe => endat_de, i_endat_data_in => endat_di);

    -- The stimulus drives and samples on the falling edge, the reader and the
    -- emulator work on the rising one: no race between them.
    stimulus : process
        variable rng : emu_random_t;
        variable set, got, sent : unsigned(BITS - 1 downto 0);
        variable error1, error2 : integer;
    begin
        rng.seed(7);
        read_pos <= '0';
        for i in 1 to 3 loop
            wait until falling_edge(clk);
        end loop;
        rst_n <= '1';
        for n in 0 to READS - 1 loop
            set := resize(rng.random32, BITS);
            error1 := to_integer(rng.random32(0 downto 0));
            error2 := to_integer(rng.random32(0 downto 0));
            set_position("u_emu", 0, resize(set, 64));
            set_status("u_emu", 0, "f1", error1);
            set_status("u_emu", 0, "f2", error2);
            read_pos <= '1';
            wait until falling_edge(clk);
            read_pos <= '0';
            wait until falling_edge(clk) and (done = '1' or timeout = '1');
            got := pos;
            if n = FLIP_READ and FLIP_BIT >= 0 then
                got(FLIP_BIT) := not got(FLIP_BIT);
            end if;
            sent := resize(last_value("u_emu", 0), BITS);
            -- F1 is 1 on an error, F2 0 (seed 004 2.3.1.2).
            assert timeout = '0' and got = sent and got = set and crc_good = '1'
                   and (f1 = '1') = (error1 = 1) and (f2 = '0') = (error2 = 1)
                report "read " & integer'image(n) & ": reader " & to_hstring(got) & " F1 " & std_logic'image(f1)
                       & " F2 " & std_logic'image(f2) & " crc_good " & std_logic'image(crc_good) & " timeout "
                       & std_logic'image(timeout) & "; emulator sent " & to_hstring(sent) & " error 1 "
                       & integer'image(error1) & " error 2 " & integer'image(error2)
                severity failure;
            wait until falling_edge(clk) and busy = '0';
            assert count("u_mon") = n + 1 and resize(last_value("u_mon", 0), BITS) = got
                   and last_status("u_mon", 0, "crc_ok") = 1
                report "read " & integer'image(n) & ": the monitor decoded " & integer'image(count("u_mon"))
                       & " transfers, the last position " & to_hstring(last_value("u_mon", 0)) & "; the reader read "
                       & to_hstring(got) severity failure;
        end loop;
        assert violations("u_emu") = 0 and violations("u_mon") = 0
            report "the reader broke " & integer'image(violations("u_emu")) & " + " & integer'image(violations("u_mon"))
                   & " timing rule(s) of EnDat (PROTOCOL VIOLATION lines above)" severity failure;
        report "PASS endat22_reader: " & integer'image(READS)
               & " reads equal to what the emulator sent and the monitor decoded, "
               & integer'image(now / PERIOD) & " cycles";
        std.env.finish;
    end process;
end architecture;
