# emu_vhdl.mk: what a VHDL testbench's Makefile needs to use the emulators
# and monitors of encoder-tb in GHDL, included after hdl/emu/emu.mk with
#
#   EMU_VHDL := ssi_encoder_emu ssi_monitor    the entities the bench uses
#   SOURCES := my_master.vhd tb_my_master.vhd  the user's files, in order
#   TOP := tb_my_master
#
#   GHDL_RUN_ARGS := -gREADS=$(READS)          the run's generics and plusargs
#
# It analyses the packages, those entities and SOURCES into build/ (GHDL's
# work library) and elaborates TOP when any of them changed:
# build/$(TOP).stamp. GHDL's mcode backend loads libcosim.so when it
# analyses emu_ffi.vhd, so analysis runs under RUN_ENV too. `make ghdl`
# runs TOP ($(RUN_ENV) ghdl -r $(GHDL_FLAGS) $(TOP) $(GHDL_RUN_ARGS));
# `make clean` removes build/.

EMU_VHDL_DIR := $(EMU_HDL_DIR)/vhdl
GHDL_FLAGS := --std=08 --workdir=build
EMU_VHDL_SOURCES := $(EMU_VHDL_DIR)/emu_ffi.vhd $(EMU_VHDL_DIR)/emu_pkg.vhd $(EMU_VHDL_DIR)/emu_random_pkg.vhd $(EMU_VHDL_DIR)/emu_core.vhd \
    $(patsubst %,$(EMU_VHDL_DIR)/%.vhd,$(EMU_VHDL))

build/$(TOP).stamp: $(EMU_VHDL_SOURCES) $(SOURCES) $(EMU_LIB_DIR)/libcosim.so
	mkdir -p build
	$(RUN_ENV) ghdl -a $(GHDL_FLAGS) $(EMU_VHDL_SOURCES) $(SOURCES)
	$(RUN_ENV) ghdl -e $(GHDL_FLAGS) $(TOP)
	touch $@

.PHONY: ghdl clean
ghdl: build/$(TOP).stamp
	$(RUN_ENV) ghdl -r $(GHDL_FLAGS) $(TOP) $(GHDL_RUN_ARGS)

clean:
	rm -rf build
