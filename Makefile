# Encoder-interface reference models and testbench generator.
#
#   make demo        vectors, waves and transcript of the seed SSI scenario in out/
#   make test        everything: cargo tests, every core's vectors in Icarus and
#                    Verilator, committed vectors == fresh ones, Verilator lint,
#                    clippy, every .gtkw layout opened in GTKWave (headless)
#   make vectors     regenerate vectors/<core>/ from the built-in scenarios
#   make sim CORE=ssi_master SIM=icarus|verilator [SCENARIO=ssi_seed_12bit] [WAVES=1]
#                    SCENARIO may also be a scenario file (my_ssi.toml: generated
#                    into build/custom/ first) or a vector file (path/x.hex); the
#                    core is then the file's own and CORE may be left out
#   make waves CORE=ssi_master [SCENARIO=ssi_seed_12bit|my_ssi.toml]   open GTKWave on the saved layout
#   make synth       yosys + nextpnr-ice40 (hx8k) for every core: logic cells and Fmax
#   make bench       model vs Verilator vs Icarus cycles per second
#   make cosim       every core closed-loop against its encoder emulator (both simulators)
#   make soak        long runs: 100000 closed-loop transactions per core, the campaigns
#   make coverage    RTL line/branch/toggle coverage of every core, against the baseline
#   make mutate      mutation score of every core (long)
#   make formal      every core's properties proven (SymbiYosys), docs/formal.md written;
#                    a core broken on purpose must fail with a trace GTKWave opens
#   make deps        install Icarus, Verilator, GHDL, yosys, nextpnr, GTKWave, sigrok-cli,
#                    SymbiYosys and the Python packages if missing

# Empty: make sim takes the core from a scenario file, else ssi_master.
CORE ?=
SIM ?= icarus
WAVES ?= 0
SCENARIO ?=
CARGO ?= cargo
TBGEN := target/release/tbgen

.PHONY: all demo vectors test deps build cargo-test hdl-test check-vectors check-gtkw lint clippy sim waves synth bench cosim soak coverage mutate formal clean

all: vectors

deps:
	@scripts/deps.sh

build:
	$(CARGO) build --release --locked -p tbgen

demo: build
	$(TBGEN) gen ssi_seed_12bit --out out
	@echo "open the waves with: gtkwave out/ssi_seed_12bit.gtkw"

vectors: build
	$(TBGEN) gen --all --out vectors

# Every check, stage by stage with its wall and CPU time (xtask/: the stages,
# their order and parallelism as code; `target/release/xtask test --list`),
# two at a time, the replays beside the Rust build.
test:
	@$(CARGO) build --release --locked -q -p xtask
	@target/release/xtask test

# The release profile, the one tbgen is built with (make test compiles every
# crate once); the workspace's crates keep overflow checks and debug
# assertions in it (Cargo.toml), so arithmetic overflow panics in tests.
cargo-test:
	$(CARGO) test --release --workspace --locked

lint:
	@scripts/lint.sh

clippy:
	@scripts/clippy.sh

hdl-test:
	@scripts/regress.sh

check-vectors: build
	@scripts/check_vectors.sh

check-gtkw:
	@scripts/check_gtkw.sh

sim:
	@scripts/regress.sh $(if $(CORE),--core $(CORE),$(if $(SCENARIO),,--core ssi_master)) --sim $(SIM) $(if $(SCENARIO),--scenario $(SCENARIO)) $(if $(filter 1,$(WAVES)),--waves)

waves:
	@core="$(or $(CORE),ssi_master)"; scenario="$(SCENARIO)"; \
	 case "$$scenario" in \
	 *.toml) layout=$$(ls build/custom/$$(basename "$$scenario" .toml)/*.gtkw 2>/dev/null | head -n 1); \
	         [ -n "$$layout" ] || { echo "make waves: no layout for $$scenario in build/custom/ (run make sim SCENARIO=$$scenario first)" >&2; exit 2; } ;; \
	 "") layout=$$(ls vectors/$$core/*.gtkw | head -n 1) ;; \
	 *) layout=vectors/$$core/$$scenario.gtkw ;; \
	 esac; \
	 gtkwave "$$layout"

# Every core closed-loop against its encoder emulator (hdl/emu/, the cosim
# library), 1000 transactions per core in each simulator.
cosim:
	@scripts/cosim_regress.sh --transactions 1000

# Long runs kept out of make test: at least 100000 closed-loop transactions
# per core (Verilator; every configuration at least a tenth of them, the rest
# on the core's quickest one, two cores at a time) and the model's corruption
# campaigns, with their counts; and 1000 per core over every configuration
# in Icarus (make test runs Icarus on each core's cheapest configuration only).
soak:
	@scripts/soak.sh --transactions 100000
	@scripts/cosim_regress.sh --sim icarus --transactions 1000
	$(CARGO) test --release --locked -p model campaign -- --nocapture

# RTL line, branch and toggle coverage of every core over its vectors,
# against hdl/coverage/baseline.txt (make test reports it from its own
# Verilator replays).
coverage:
	@scripts/coverage.sh

# Mutants of each core replayed against its vectors (long: not in make test):
# 30 scored per core, seed 1, the figures in docs/performance.md. modbus_master's
# draw holds one mutant that does not build (a generate loop counting down
# forever), so 31 are drawn there for 30 scored.
mutate:
	@status=0; for d in vectors/*/; do core=$$(basename "$$d"); n=30; [ "$$core" = modbus_master ] && n=31; \
	    python3 scripts/mutate.py "$$core" --count $$n --seed 1 || status=1; done; exit $$status

synth:
	@scripts/synth.sh

# Every task of every core's properties (hdl/formal/<core>/): per property
# proven / bounded to depth N / failed, the table written to docs/formal.md;
# then a counter one short in a copy of a core must fail its proof with a
# VCD that GTKWave opens (hdl/formal/test_broken_rule.py).
formal:
	@.venv/bin/python scripts/formal.py --doc docs/formal.md
	@.venv/bin/python -m pytest -p no:cacheprovider -q hdl/formal/test_broken_rule.py

# Model, VCD writer, Verilator and Icarus on the same vectors, the closed
# loop per core in both simulators, the campaigns (columns: scripts/bench.sh).
bench: build
	@scripts/bench.sh

clean:
	rm -rf build out
