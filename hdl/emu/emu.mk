# emu.mk: what a testbench's Makefile needs to use the emulators and
# monitors of encoder-tb, included after ENCODER_TB names the checkout:
#
#   ENCODER_TB ?= ../..
#   ifeq ($(wildcard $(ENCODER_TB)/hdl/emu/emu.mk),)
#   $(error ENCODER_TB=$(ENCODER_TB) is not an encoder-tb checkout ...)
#   endif
#   include $(ENCODER_TB)/hdl/emu/emu.mk
#
# It builds the emulator library and its Icarus VPI module when they are out
# of date (scripts/emu_lib.sh: the first build of a clone takes a few
# minutes and says so) and sets:
#
#   EMU_LIB_DIR   libcosim.so (Verilator: -LDFLAGS "-L$(EMU_LIB_DIR) -lcosim -Wl,-rpath,$(EMU_LIB_DIR)")
#   EMU_VPI_DIR   emu.vpi (Icarus: vvp -M $(EMU_VPI_DIR) -m emu tb.vvp)
#   EMU_HDL_DIR   the wrappers, monitors and their includes (-I)
#   RUN_ENV       the library just built ahead of any older libcosim.so on
#                 the caller's LD_LIBRARY_PATH (cargo test puts its own first)
#
# Each may be given on the command line instead (make EMU_HDL_DIR=...).

EMU_VARS := $(shell $(ENCODER_TB)/scripts/emu_lib.sh)
ifeq ($(filter EMU_LIB_DIR=%,$(EMU_VARS)),)
$(error $(ENCODER_TB)/scripts/emu_lib.sh could not build the emulator library (its messages are above); run it by hand to see why)
endif
EMU_LIB_DIR ?= $(patsubst EMU_LIB_DIR=%,%,$(filter EMU_LIB_DIR=%,$(EMU_VARS)))
EMU_VPI_DIR ?= $(patsubst EMU_VPI_DIR=%,%,$(filter EMU_VPI_DIR=%,$(EMU_VARS)))
EMU_HDL_DIR ?= $(patsubst EMU_HDL_DIR=%,%,$(filter EMU_HDL_DIR=%,$(EMU_VARS)))
RUN_ENV := LD_LIBRARY_PATH=$(EMU_LIB_DIR)$${LD_LIBRARY_PATH:+:$$LD_LIBRARY_PATH}
