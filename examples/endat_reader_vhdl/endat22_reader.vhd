-- endat22_reader: an EnDat 2.2 position reader written in VHDL from the
-- HEIDENHAIN EnDat 2.2 document (seed 004) alone to prove the VHDL
-- emulators; unlike encoder-tb's endat_master and
-- examples/endat_reader_other: its own ports, a synchronous active-low
-- reset, the request taken in the cycle it is seen, the type 2.2 command
-- "Encoder send position values with additional data" (111000, none
-- selected: start bit, F1, F2, position LSB first, CRC; seed 004 2.3.1.2),
-- each bit taken SAMPLE system clocks after the RISING clock edge that put
-- it on the line (after a 2-flop synchroniser; the others sample in the low
-- phase), the CRC (the seed's MakeCrcPos, appendix A4) computed over the
-- received frame once it is complete, and the value reported at the last
-- CRC bit, a period before the clock stops (busy stays high until the line
-- is high again and t_R has passed).
--
--   clk  ‾‾\___/‾‾\__/‾‾\__ ... _/‾‾\__/‾‾\__/‾ ... ‾‾\__/‾‾\__/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
--        F1  R1  F2  R2        F7  R7  F8       C0 put ^  ^ one period on, the clock stops high
--   de   ______/‾‾‾‾‾‾‾ M2 M1 M0 (M2) (M1) (M0) ‾‾\______________________________
--   rx   ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_ ... _/S\_F1_F2_P0 ... Pn-1_C4 ... C0\_ t_m _/‾
--                                    bit k taken SAMPLE clocks after R_k
--
-- The mode bits go out at the falling edges F2 to F7 (the encoder takes each
-- at the next rising edge), the driver is on from F2 and off at F8; then the
-- reader keeps clocking and takes one bit per period until the start bit
-- (at most POLL_MAX periods after F1).

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity endat22_reader is
    generic (
        POS_BITS : positive := 21;
        HALF : positive := 16;      -- system clocks per clock half period
        SAMPLE : positive := 13;    -- system clocks after a rising edge to take the bit (< HALF)
        POLL_MAX : positive := 40;  -- clock periods after F1 to find the start bit
        T_R : positive := 32;       -- the line high this long before the next read (>= 500 ns), system clocks
        T_ERR : positive := 512     -- the wait after a read without start bit (>= 30 us), system clocks
    );
    port (
        clk : in std_logic;
        rst_n : in std_logic;
        read_pos : in std_logic;
        busy : out std_logic;
        done : out std_logic;                  -- one cycle: the outputs below are new
        pos : out unsigned(POS_BITS - 1 downto 0);
        f1 : out std_logic;                    -- as on the line: 1 = error
        f2 : out std_logic;                    -- as on the line: 0 = error 2
        crc_good : out std_logic;
        timeout : out std_logic;               -- one cycle: no start bit within POLL_MAX periods
        endat_clk : out std_logic := '1';
        endat_de : out std_logic := '0';
        endat_do : out std_logic := '1';
        endat_di : in std_logic
    );
end entity;

architecture rtl of endat22_reader is
    constant MODE : std_logic_vector(5 downto 0) := "111000";   -- sent left to right
    constant FRAME : positive := 2 + POS_BITS + 5;               -- F1, F2, position, CRC
    type state_t is (idle, clocking, recovery_low, recovery_high, rest);
    signal state : state_t := idle;
    signal tick : natural range 0 to 2 * HALF := 0;
    signal period : natural range 0 to POLL_MAX + FRAME + 1 := 0;    -- 1 = the period from F1
    signal started : boolean := false;
    signal finishing : boolean := false;
    signal taken : natural range 0 to FRAME := 0;
    signal bits : std_logic_vector(FRAME - 1 downto 0) := (others => '0');   -- first bit in the highest
    signal sync : std_logic_vector(1 downto 0) := "11";
    signal timer : natural range 0 to T_R + T_ERR := 0;

    -- MakeCrcPos (seed 004, A4) over F1, F2 and the position LSB first: the
    -- register starts at all ones, and the CRC on the line is its inverse.
    function crc5(data : std_logic_vector) return std_logic_vector is
        variable ff : std_logic_vector(4 downto 0) := (others => '1');
        variable ex : std_logic;
    begin
        for i in data'range loop
            ex := ff(4) xor data(i);
            ff := ff(3) & (ff(2) xor ex) & ff(1) & (ff(0) xor ex) & ex;
        end loop;
        return not ff;
    end function;
begin
    busy <= '0' when state = idle else '1';

    process (clk)
        variable rx : std_logic;
        variable position : unsigned(POS_BITS - 1 downto 0);
    begin
        if rising_edge(clk) then
            sync <= sync(0) & endat_di;
            rx := sync(1);
            done <= '0';
            timeout <= '0';
            if rst_n = '0' then
                state <= idle;
                endat_clk <= '1';
                endat_de <= '0';
                endat_do <= '1';
            else
                case state is
                    when idle =>
                        if read_pos = '1' then
                            endat_clk <= '0';     -- F1: the encoder stores the position
                            tick <= 0;
                            period <= 1;
                            started <= false;
                            taken <= 0;
                            state <= clocking;
                        end if;
                    when clocking =>
                        -- One period: low for HALF clocks from F_k, high for
                        -- HALF from R_k.
                        if tick = 2 * HALF - 1 then
                            tick <= 0;
                            period <= period + 1;
                            endat_clk <= '0';                 -- F_(period + 1)
                            if period + 1 >= 2 and period + 1 <= 7 then
                                endat_de <= '1';
                                endat_do <= MODE(7 - (period + 1));
                            elsif period + 1 = 8 then
                                endat_de <= '0';
                                endat_do <= '1';
                            end if;
                        else
                            tick <= tick + 1;
                        end if;
                        if tick = HALF - 1 then
                            endat_clk <= '1';                 -- R_period
                            if finishing then
                                -- One period after the last bit's (the
                                -- falling edge a master reads it at in the
                                -- seed's diagrams), the clock stops high.
                                finishing <= false;
                                state <= recovery_low;
                            end if;
                        end if;
                        -- The bit R_k put on the line, SAMPLE clocks after R_k.
                        if tick = HALF - 1 + SAMPLE and period >= 8 then
                            if not started then
                                if rx = '1' then
                                    started <= true;
                                elsif period >= POLL_MAX then
                                    -- No start bit: the clock stops high,
                                    -- and the next read waits T_ERR (seed
                                    -- 004 A2 4.2.1: 30 us after an error).
                                    timeout <= '1';
                                    timer <= T_ERR - 1;
                                    state <= rest;
                                end if;
                            else
                                bits <= bits(FRAME - 2 downto 0) & rx;
                                taken <= taken + 1;
                                if taken = FRAME - 1 then
                                    done <= '1';
                                    finishing <= true;
                                end if;
                            end if;
                        end if;
                    when recovery_low =>
                        if rx = '0' then
                            state <= recovery_high;
                        end if;
                    when recovery_high =>
                        if rx = '1' then
                            timer <= T_R - 1;
                            state <= rest;
                        end if;
                    when rest =>
                        if timer = 0 then
                            state <= idle;
                        else
                            timer <= timer - 1;
                        end if;
                end case;
            end if;
        end if;
    end process;

    -- The frame's fields, read from the register once it is complete (done
    -- is high in the cycle after the last bit went in).
    f1 <= bits(FRAME - 1);
    f2 <= bits(FRAME - 2);
    fields : for i in 0 to POS_BITS - 1 generate
        pos(i) <= bits(FRAME - 3 - i);           -- LSB first on the line
    end generate;
    crc_good <= '1' when crc5(bits(FRAME - 1 downto 5)) = bits(4 downto 0) else '0';
end architecture;
