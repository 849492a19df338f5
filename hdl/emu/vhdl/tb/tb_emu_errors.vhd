-- tb_emu_errors: bad input to a VHDL emulator, one case per run
-- (scripts/vhdl_examples.sh runs each and checks the message): the
-- configuration from the plusarg +ssi_emu_config=<file> (none, a missing
-- file, a bad field), X on the emulator's input at X_AT_NS after it was 1
-- (STOP_ON_X 1 stops the run, 0 reports it and goes on), a control naming
-- no instance (CALL_NAME).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.emu_pkg.all;

entity tb_emu_errors is
    generic (
        X_AT_NS : integer := -1;
        STOP_ON_X : integer := 1;
        CALL_NAME : string := "u_emu"
    );
end entity;

architecture bench of tb_emu_errors is
    signal clk : std_logic := '0';
    signal ssi_clk : std_logic := '1';
    signal ssi_data : std_logic;
begin
    clk <= not clk after 62.5 ns;

    u_emu : entity work.ssi_encoder_emu
        generic map (F_EMU_HZ => 8000000, STOP_ON_X => STOP_ON_X)
        port map (i_emu_clk => clk, i_ssi_clk => ssi_clk, o_ssi_data => ssi_data);

    process
    begin
        set_position(CALL_NAME, 0, to_unsigned(5, 64));
        if X_AT_NS >= 0 then
            wait for X_AT_NS * 1 ns;
            ssi_clk <= 'X';
            wait for 500 ns;
            ssi_clk <= '1';
        end if;
        wait for 1 us;
        report "END tb_emu_errors";
        std.env.finish;
    end process;
end architecture;
