-- tformat_edge_reader: a Tamagawa T-format reader written in VHDL from the
-- Smart Abs TS5669 N127 specification (seed 002) alone to prove the VHDL
-- emulators; unlike encoder-tb's tformat_host and
-- examples/tformat_reader_other: its own ports, an asynchronous active-low
-- reset, the request taken in the cycle it is seen, Data ID 0 (ABS) and
-- Data ID 1 (ABM), a receiver that re-aligns its bit clock on EVERY falling
-- edge of the line (not only on start bits) and takes one sample in the
-- middle of each bit, and the answer reported at the last data bit of its
-- CRC field, before that field's delimiter.
--
-- One read (seed 002 6.2.1, Table 2): the control field CF, then the answer
-- CF SF D0 D1 D2 CRC (ID 0: ABS0..ABS2, ID 1: ABM0..ABM2), each field a
-- start bit 0, 8 bits LSB first and a delimiter 1 (6.3). Checked: the answer
-- within TIMEOUT cycles; every start bit and delimiter; CF equal to the
-- request's; SF's ca0 (bit 6) and ca1 (bit 7) clear; the CRC (6.3.4: G(X) =
-- X^8 + 1 over every field but the CRC, bit by bit: the XOR of their bytes).
-- CF: sink code 010 in bits 0..2, the Data ID in bits 3..6, their parity in
-- bit 7 (ID 0 = 0x02, ID 1 = 0x8A).
--
--   de ___/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\__________________________________________________
--   tx ‾‾‾\_S_c0..c7_/‾D‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
--   rx ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾ ~3 us ‾‾\_S_CF_D_S_SF_D_ ... _S_CRC_D‾‾‾‾‾‾‾‾‾
--                                                             ^ valid

library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity tformat_edge_reader is
    generic (
        BIT_CLOCKS : positive := 16;    -- system clocks per bit (40 MHz / 2.5 Mbps)
        TIMEOUT : positive := 800       -- cycles from the request's end to the answer's first start bit
    );
    port (
        clk : in std_logic;
        rst_n : in std_logic;
        request : in std_logic;
        data_id : in std_logic;        -- 0: ABS (Data ID 0), 1: ABM (Data ID 1)
        busy : out std_logic;
        valid : out std_logic;         -- one cycle: a good answer; abs_pos or abm_pos is new
        fail : out std_logic;          -- one cycle: no answer, or one that failed a check
        abs_pos : out unsigned(16 downto 0);
        abm_pos : out unsigned(15 downto 0);
        sf : out std_logic_vector(7 downto 0);
        de : out std_logic := '0';
        tx : out std_logic := '1';
        rx : in std_logic
    );
end entity;

architecture rtl of tformat_edge_reader is
    constant FIELDS : positive := 6;
    type byte_array is array (0 to FIELDS - 1) of std_logic_vector(7 downto 0);
    type state_t is (idle, send, listen, field, between, drain);
    signal state : state_t := idle;
    signal timer : natural range 0 to TIMEOUT := 0;
    signal frame : std_logic_vector(9 downto 0);      -- the request, first bit in bit 0
    signal sent : natural range 0 to 10 := 0;
    signal cf : std_logic_vector(7 downto 0);
    signal id_q : std_logic := '0';
    signal sync : std_logic_vector(1 downto 0) := "11";
    signal last : std_logic := '1';
    signal phase : natural range 0 to BIT_CLOCKS - 1 := 0;
    signal idx : natural range 0 to 9 := 0;           -- bit of the field: 0 start, 1..8 data, 9 delimiter
    signal nfield : natural range 0 to FIELDS := 0;
    signal bytes : byte_array;
    signal shift : std_logic_vector(7 downto 0);
begin
    busy <= '0' when state = idle else '1';

    process (clk, rst_n)
        variable line : std_logic;
        variable falling : boolean;
        variable sample : boolean;
        variable crc : std_logic_vector(7 downto 0);
        variable byte : std_logic_vector(7 downto 0);
        variable good : boolean;
    begin
        if rst_n = '0' then
            state <= idle;
            de <= '0';
            tx <= '1';
            sync <= "11";
            last <= '1';
            valid <= '0';
            fail <= '0';
        elsif rising_edge(clk) then
            sync <= sync(0) & rx;
            line := sync(1);
            last <= line;
            falling := last = '1' and line = '0';
            valid <= '0';
            fail <= '0';
            -- The bit clock: a falling edge is a bit boundary. Seen before
            -- this bit's sample it moves the sample to BIT_CLOCKS/2 after
            -- it; seen after, it begins the next bit.
            sample := false;
            if falling and phase >= BIT_CLOCKS / 2 and state = field then
                phase <= 0;
                idx <= idx + 1 when idx < 9 else 9;
            elsif falling then
                phase <= 0;
            elsif phase = BIT_CLOCKS - 1 then
                phase <= 0;
                if state = field and idx < 9 then
                    idx <= idx + 1;
                end if;
            else
                phase <= phase + 1;
                sample := phase = BIT_CLOCKS / 2 - 1;
            end if;
            case state is
                when idle =>
                    if request = '1' then
                        -- Parity, the Data ID (0 or 1) and the sink code.
                        byte := data_id & "000" & data_id & "010";
                        cf <= byte;
                        frame <= '1' & byte & '0';         -- delimiter, CF, start bit
                        id_q <= data_id;
                        de <= '1';
                        tx <= '0';
                        sent <= 0;
                        timer <= BIT_CLOCKS - 1;
                        state <= send;
                    end if;
                when send =>
                    if timer = 0 then
                        if sent = 9 then
                            de <= '0';
                            tx <= '1';
                            timer <= TIMEOUT - 1;
                            nfield <= 0;
                            state <= listen;
                        else
                            sent <= sent + 1;
                            tx <= frame(sent + 1);
                            timer <= BIT_CLOCKS - 1;
                        end if;
                    else
                        timer <= timer - 1;
                    end if;
                when listen | between =>
                    if falling then
                        idx <= 0;
                        state <= field;
                    elsif state = listen and timer = 0 then
                        fail <= '1';
                        state <= idle;
                    elsif state = listen then
                        timer <= timer - 1;
                    end if;
                when field =>
                    if sample then
                        if idx = 0 and line /= '0' then
                            fail <= '1';
                            timer <= 2 * BIT_CLOCKS;
                            state <= drain;
                        elsif idx >= 1 and idx <= 8 then
                            byte := line & shift(7 downto 1);    -- LSB first
                            shift <= byte;
                            if idx = 8 then
                                bytes(nfield) <= byte;
                                if nfield = FIELDS - 1 then
                                    -- The CRC field's last data bit: check and report.
                                    crc := x"00";
                                    for k in 0 to FIELDS - 2 loop
                                        crc := crc xor bytes(k);
                                    end loop;
                                    good := bytes(0) = cf and bytes(1)(7 downto 6) = "00" and crc = byte;
                                    if good then
                                        valid <= '1';
                                        if id_q = '0' then
                                            abs_pos <= unsigned(std_logic_vector'(bytes(4)(0) & bytes(3) & bytes(2)));
                                        else
                                            abm_pos <= unsigned(std_logic_vector'(bytes(3) & bytes(2)));
                                        end if;
                                        sf <= bytes(1);
                                    else
                                        fail <= '1';
                                    end if;
                                end if;
                            end if;
                        elsif idx = 9 then
                            if line /= '1' then
                                fail <= '1';
                                timer <= 2 * BIT_CLOCKS;
                                state <= drain;
                            elsif nfield = FIELDS - 1 then
                                timer <= 2 * BIT_CLOCKS;
                                state <= drain;
                            else
                                nfield <= nfield + 1;
                                state <= between;
                            end if;
                        end if;
                    end if;
                when drain =>
                    -- The line high for two bit times ends the answer (7.2).
                    if line = '0' then
                        timer <= 2 * BIT_CLOCKS;
                    elsif timer = 0 then
                        state <= idle;
                    else
                        timer <= timer - 1;
                    end if;
            end case;
        end if;
    end process;
end architecture;
