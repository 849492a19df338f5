-- biss_aligned_reader: a BiSS-C reader for one slave, written in VHDL from
-- the SAR58K24 manual's BiSS-C section alone to prove the VHDL emulators;
-- unlike encoder-tb's biss_master and examples/biss_reader_other: its own
-- ports, an asynchronous active-high reset, the request taken in the cycle
-- it is seen, and line-delay compensation by alignment: the reader times
-- every bit from the start bit's rising edge as it arrives (oversampled at
-- the system clock) and takes it in the middle of its cell, whatever the
-- cable's delay; the CRC runs bit by bit as the bits arrive; the value is
-- reported at the last CRC bit, before the slave's timeout ends (busy stays
-- high until SLO is high again).
--
--   ma   ‾‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/ ... ‾‾\__/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
--   slo  ‾‾‾‾‾‾‾‾‾‾‾‾‾‾\______/‾‾‾‾‾\_CDS_X_D17_X ... X_CRC0_X___ timeout ___/‾‾
--                       ack    ^ start edge: bit k sampled (k + 1.5) MA periods later
--   CDS, data MSB first, nE, nW, 6 CRC bits (x^6 + x + 1, init 0, sent inverted)

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity biss_aligned_reader is
    generic (
        DATA_BITS : positive := 18;
        HALF : positive := 16       -- system clocks per MA half period
    );
    port (
        clk : in std_logic;
        arst : in std_logic;
        req : in std_logic;
        busy : out std_logic;
        valid : out std_logic;
        data : out unsigned(DATA_BITS - 1 downto 0);
        err_n : out std_logic;
        warn_n : out std_logic;
        crc_ok : out std_logic;
        ma : out std_logic := '1';
        slo : in std_logic
    );
end entity;

architecture rtl of biss_aligned_reader is
    constant PERIOD : positive := 2 * HALF;
    -- CDS, data, nE, nW and the CRC.
    constant CELLS : positive := 1 + DATA_BITS + 2 + 6;
    type state_t is (idle, wait_ack, wait_start, cells_in, wait_low, wait_high);
    signal state : state_t := idle;
    signal ma_reg : std_logic := '1';
    signal ma_tick : natural range 0 to HALF - 1 := 0;
    signal clocking : boolean := false;
    signal sync : std_logic_vector(2 downto 0) := "111";
    signal cell_timer : natural range 0 to 2 * PERIOD := 0;
    signal cell : natural range 0 to CELLS := 0;
    signal shift : std_logic_vector(DATA_BITS + 1 downto 0) := (others => '0');
    signal crc, crc_in : std_logic_vector(5 downto 0) := (others => '0');
begin
    ma <= ma_reg;
    busy <= '0' when state = idle else '1';

    process (clk, arst)
        variable bit_in : std_logic;
        variable fb : std_logic;
    begin
        if arst = '1' then
            state <= idle;
            ma_reg <= '1';
            clocking <= false;
            ma_tick <= 0;
            sync <= "111";
            valid <= '0';
        elsif rising_edge(clk) then
            sync <= sync(1 downto 0) & slo;
            valid <= '0';
            -- MA: HALF system clocks a phase while clocking; it stops only
            -- high (a whole last period).
            if clocking then
                if ma_tick = HALF - 1 then
                    ma_tick <= 0;
                    ma_reg <= not ma_reg;
                else
                    ma_tick <= ma_tick + 1;
                end if;
            end if;
            bit_in := sync(1);
            case state is
                when idle =>
                    if req = '1' and bit_in = '1' then
                        clocking <= true;
                        ma_reg <= '0';
                        ma_tick <= 0;
                        state <= wait_ack;
                    end if;
                when wait_ack =>
                    if bit_in = '0' then
                        state <= wait_start;
                    end if;
                when wait_start =>
                    if bit_in = '1' then
                        -- The start bit's cell began at this edge: the next
                        -- cell's middle is 1.5 periods on.
                        cell_timer <= PERIOD + HALF - 1;
                        cell <= 0;
                        crc <= (others => '0');
                        state <= cells_in;
                    end if;
                when cells_in =>
                    if cell_timer = 0 then
                        cell_timer <= PERIOD - 1;
                        cell <= cell + 1;
                        if cell >= 1 and cell <= DATA_BITS + 2 then
                            shift <= shift(DATA_BITS downto 0) & bit_in;
                            fb := crc(5) xor bit_in;
                            crc <= crc(4 downto 0) & '0';
                            if fb = '1' then
                                crc <= (crc(4 downto 0) & '0') xor "000011";
                            end if;
                        elsif cell > DATA_BITS + 2 then
                            crc_in <= crc_in(4 downto 0) & bit_in;
                        end if;
                        if cell = CELLS - 1 then
                            state <= wait_low;
                        end if;
                    else
                        cell_timer <= cell_timer - 1;
                    end if;
                when wait_low =>
                    -- The last CRC bit is in crc_in now: report, then let
                    -- MA end high and wait out the slave's timeout.
                    if valid = '0' and cell = CELLS then
                        data <= unsigned(shift(DATA_BITS + 1 downto 2));
                        err_n <= shift(1);
                        warn_n <= shift(0);
                        if crc_in = not crc then crc_ok <= '1'; else crc_ok <= '0'; end if;
                        valid <= '1';
                        cell <= 0;
                    end if;
                    if ma_reg = '1' and ma_tick = 0 then
                        clocking <= false;
                    end if;
                    if bit_in = '0' then
                        state <= wait_high;
                    end if;
                when wait_high =>
                    if ma_reg = '1' and ma_tick = 0 then
                        clocking <= false;
                    end if;
                    if bit_in = '1' and not clocking then
                        state <= idle;
                    end if;
            end case;
        end if;
    end process;
end architecture;
