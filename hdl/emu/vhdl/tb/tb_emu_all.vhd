-- tb_emu_all: every VHDL emulator and monitor opened from the cocotb
-- examples' configurations (hdl/cocotb/configs/) at their clocks and stepped
-- for 100 us on idle lines: each kind and its library name, each entity's
-- pin order and idle levels (no X, no violation). scripts/vhdl_examples.sh
-- runs it with CONFIGS set to that directory.
library ieee;
use ieee.std_logic_1164.all;
use work.emu_pkg.all;

entity tb_emu_all is
    generic (CONFIGS : string := "hdl/cocotb/configs");
end entity;

architecture bench of tb_emu_all is
    signal clk_0_25, clk_4, clk_8, clk_20, clk_80 : std_logic := '0';
    constant hi : std_logic := '1';
    constant lo : std_logic := '0';
begin
    clk_0_25 <= not clk_0_25 after 2000 ns;
    clk_4 <= not clk_4 after 125 ns;
    clk_8 <= not clk_8 after 62.5 ns;
    clk_20 <= not clk_20 after 25 ns;
    clk_80 <= not clk_80 after 6.25 ns;

    u_ssi_encoder_emu : entity work.ssi_encoder_emu
        generic map (CONFIG => CONFIGS & "/ssi.toml", F_EMU_HZ => 4000000)
        port map (i_emu_clk => clk_4, i_ssi_clk => hi, o_ssi_data => open);
    u_biss_slave_emu : entity work.biss_slave_emu
        generic map (CONFIG => CONFIGS & "/biss.toml", F_EMU_HZ => 80000000)
        port map (i_emu_clk => clk_80, i_ma => hi, o_slo => open);
    u_endat_encoder_emu : entity work.endat_encoder_emu
        generic map (CONFIG => CONFIGS & "/endat.toml", F_EMU_HZ => 8000000)
        port map (i_emu_clk => clk_8, i_endat_clk => hi, i_endat_data => hi, i_endat_data_oe => lo, o_endat_data => open, o_endat_data_oe => open);
    u_tformat_encoder_emu : entity work.tformat_encoder_emu
        generic map (CONFIG => CONFIGS & "/tformat.toml", F_EMU_HZ => 20000000)
        port map (i_emu_clk => clk_20, i_tf_data => hi, i_tf_data_oe => lo, o_tf_data => open, o_tf_data_oe => open);
    u_esl_encoder_emu : entity work.esl_encoder_emu
        generic map (CONFIG => CONFIGS & "/esl.toml", F_EMU_HZ => 80000000)
        port map (i_emu_clk => clk_80, i_esl_data => hi, i_esl_data_oe => lo, o_esl_data => open, o_esl_data_oe => open);
    u_sar58k24_encoder_emu : entity work.sar58k24_encoder_emu
        generic map (CONFIG => CONFIGS & "/sar58k24.toml", F_EMU_HZ => 250000)
        port map (i_emu_clk => clk_0_25, i_line => hi, i_line_en => lo, i_trigger => hi, i_clr => hi, o_line => open, o_line_en => open, o_bus => open);
    u_modbus_device_emu : entity work.modbus_device_emu
        generic map (CONFIG => CONFIGS & "/modbus.toml", F_EMU_HZ => 250000)
        port map (i_emu_clk => clk_0_25, i_line => hi, i_line_en => lo, o_line => open, o_line_en => open, o_bus => open);
    u_can_node_emu : entity work.can_node_emu
        generic map (CONFIG => CONFIGS & "/can.toml", F_EMU_HZ => 4000000)
        port map (i_emu_clk => clk_4, i_can_tx => hi, o_can_rx => open);
    u_canopen_encoder_emu : entity work.canopen_encoder_emu
        generic map (CONFIG => CONFIGS & "/sar58k24_can.toml", F_EMU_HZ => 4000000)
        port map (i_emu_clk => clk_4, i_can_tx => hi, o_can_rx => open);
    u_ssi_monitor : entity work.ssi_monitor
        generic map (CONFIG => CONFIGS & "/ssi.toml", F_MON_HZ => 4000000)
        port map (i_mon_clk => clk_4, i_ssi_clk => hi, i_ssi_data => hi);
    u_biss_monitor : entity work.biss_monitor
        generic map (CONFIG => CONFIGS & "/biss.toml", F_MON_HZ => 80000000)
        port map (i_mon_clk => clk_80, i_ma => hi, i_slo => hi);
    u_endat_monitor : entity work.endat_monitor
        generic map (CONFIG => CONFIGS & "/endat.toml", F_MON_HZ => 8000000)
        port map (i_mon_clk => clk_8, i_endat_clk => hi, i_endat_data => hi, i_endat_data_oe => lo, i_endat_data_in => hi);
    u_tformat_monitor : entity work.tformat_monitor
        generic map (CONFIG => CONFIGS & "/tformat.toml", F_MON_HZ => 20000000)
        port map (i_mon_clk => clk_20, i_tf_data => hi, i_tf_data_oe => lo, i_tf_rx => hi);
    u_esl_monitor : entity work.esl_monitor
        generic map (CONFIG => CONFIGS & "/esl.toml", F_MON_HZ => 80000000)
        port map (i_mon_clk => clk_80, i_esl_data => hi, i_esl_data_oe => lo, i_esl_rx => hi);
    u_sar58k24_monitor : entity work.sar58k24_monitor
        generic map (CONFIG => CONFIGS & "/sar58k24.toml", F_MON_HZ => 250000)
        port map (i_mon_clk => clk_0_25, i_line => hi, i_line_en => lo, i_rx => hi, i_trigger => hi, i_clr => hi);
    u_modbus_monitor : entity work.modbus_monitor
        generic map (CONFIG => CONFIGS & "/modbus.toml", F_MON_HZ => 250000)
        port map (i_mon_clk => clk_0_25, i_line => hi, i_line_en => lo, i_rx => hi);
    u_can_monitor : entity work.can_monitor
        generic map (CONFIG => CONFIGS & "/can.toml", F_MON_HZ => 4000000)
        port map (i_mon_clk => clk_4, i_can_tx => hi, i_can_rx => hi);
    u_canopen_monitor : entity work.canopen_monitor
        generic map (CONFIG => CONFIGS & "/sar58k24_can.toml", F_MON_HZ => 4000000)
        port map (i_mon_clk => clk_4, i_can_tx => hi, i_can_rx => hi);

    process
    begin
        wait for 100 us;
        assert violations("u_ssi_encoder_emu") = 0 report "ssi_encoder_emu: a violation on idle lines" severity failure;
        assert violations("u_biss_slave_emu") = 0 report "biss_slave_emu: a violation on idle lines" severity failure;
        assert violations("u_endat_encoder_emu") = 0 report "endat_encoder_emu: a violation on idle lines" severity failure;
        assert violations("u_tformat_encoder_emu") = 0 report "tformat_encoder_emu: a violation on idle lines" severity failure;
        assert violations("u_esl_encoder_emu") = 0 report "esl_encoder_emu: a violation on idle lines" severity failure;
        assert violations("u_sar58k24_encoder_emu") = 0 report "sar58k24_encoder_emu: a violation on idle lines" severity failure;
        assert violations("u_modbus_device_emu") = 0 report "modbus_device_emu: a violation on idle lines" severity failure;
        assert violations("u_can_node_emu") = 0 report "can_node_emu: a violation on idle lines" severity failure;
        assert violations("u_canopen_encoder_emu") = 0 report "canopen_encoder_emu: a violation on idle lines" severity failure;
        assert violations("u_ssi_monitor") = 0 report "ssi_monitor: a violation on idle lines" severity failure;
        assert violations("u_biss_monitor") = 0 report "biss_monitor: a violation on idle lines" severity failure;
        assert violations("u_endat_monitor") = 0 report "endat_monitor: a violation on idle lines" severity failure;
        assert violations("u_tformat_monitor") = 0 report "tformat_monitor: a violation on idle lines" severity failure;
        assert violations("u_esl_monitor") = 0 report "esl_monitor: a violation on idle lines" severity failure;
        assert violations("u_sar58k24_monitor") = 0 report "sar58k24_monitor: a violation on idle lines" severity failure;
        assert violations("u_modbus_monitor") = 0 report "modbus_monitor: a violation on idle lines" severity failure;
        assert violations("u_can_monitor") = 0 report "can_monitor: a violation on idle lines" severity failure;
        assert violations("u_canopen_monitor") = 0 report "canopen_monitor: a violation on idle lines" severity failure;
        report "PASS tb_emu_all: 18 emulators and monitors opened and stepped";
        std.env.finish;
    end process;
end architecture;
