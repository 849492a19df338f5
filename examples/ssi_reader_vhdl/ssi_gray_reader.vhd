-- ssi_gray_reader: an SSI reader of a Gray-coded encoder, written in VHDL
-- from the SAR58K24 manual's SSI section alone to prove the VHDL emulators;
-- unlike encoder-tb's ssi_master and examples/ssi_reader_other: its own
-- ports, a synchronous active-high reset, the request taken in the cycle it
-- is seen (no register), the data sampled three quarters into each HIGH
-- phase of the clock (after a 2-flop synchroniser), where both sample in a
-- low phase, Gray decoded here, and the value reported at the clock's last
-- rising edge, before the rest time.
--
--   ssi_clk ‾‾‾\__________/‾‾‾‾‾‾\______/‾‾‾‾‾‾\__ ... /‾‾‾‾‾‾\______/‾‾‾‾ (REST) ‾‾
--              T_CS        HALF   HALF          bit BITS       ^ ready
--              ^ the encoder stores  ^ sample bit k at 3/4 of high phase k: bit k
--                                    is on the line a cable round trip after
--                                    rising edge k; BITS low phases after the first

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity ssi_gray_reader is
    generic (
        BITS : positive := 13;
        HALF : positive := 20;      -- system clocks per clock half period
        T_CS : positive := 44;      -- the first low phase, system clocks
        REST : positive := 280      -- clock high after a read (> the encoder's monoflop)
    );
    port (
        clk : in std_logic;
        rst : in std_logic;
        start : in std_logic;
        busy : out std_logic;
        ready : out std_logic;
        position : out unsigned(BITS - 1 downto 0);
        ssi_clk : out std_logic := '1';
        ssi_data : in std_logic
    );
end entity;

architecture rtl of ssi_gray_reader is
    type phase_t is (idle, lead, high, low, rest_phase);
    signal phase : phase_t := idle;
    signal timer : natural range 0 to REST := 0;
    signal bit_count : natural range 0 to BITS := 0;
    signal code : std_logic_vector(BITS - 1 downto 0) := (others => '0');
    signal sync : std_logic_vector(1 downto 0) := "11";

    function gray_to_binary(g : std_logic_vector) return unsigned is
        variable b : unsigned(g'length - 1 downto 0);
        variable v : std_logic_vector(g'length - 1 downto 0) := g;
    begin
        b(b'high) := v(v'high);
        for i in b'high - 1 downto 0 loop
            b(i) := b(i + 1) xor v(i);
        end loop;
        return b;
    end function;
begin
    busy <= '0' when phase = idle else '1';

    process (clk)
    begin
        if rising_edge(clk) then
            sync <= sync(0) & ssi_data;
            ready <= '0';
            if rst = '1' then
                phase <= idle;
                ssi_clk <= '1';
                timer <= 0;
                bit_count <= 0;
            else
                case phase is
                    when idle =>
                        if start = '1' then
                            ssi_clk <= '0';
                            timer <= T_CS - 1;
                            phase <= lead;
                        end if;
                    when lead | low =>
                        if timer = 0 and bit_count = BITS then
                            -- The last low phase ends the read (the encoder
                            -- counts a bit per low phase after the first).
                            ssi_clk <= '1';
                            bit_count <= 0;
                            position <= gray_to_binary(code);
                            ready <= '1';
                            timer <= REST - 1;
                            phase <= rest_phase;
                        elsif timer = 0 then
                            ssi_clk <= '1';
                            timer <= HALF - 1;
                            phase <= high;
                        else
                            timer <= timer - 1;
                        end if;
                    when high =>
                        if timer = HALF / 4 then
                            code <= code(BITS - 2 downto 0) & sync(1);
                        end if;
                        if timer = 0 then
                            bit_count <= bit_count + 1;
                            ssi_clk <= '0';
                            timer <= HALF - 1;
                            phase <= low;
                        else
                            timer <= timer - 1;
                        end if;
                    when rest_phase =>
                        if timer = 0 then
                            phase <= idle;
                        else
                            timer <= timer - 1;
                        end if;
                end case;
            end if;
        end if;
    end process;
end architecture;
