# Encoder-interface reference models and testbench generator.
#
#   make demo        vectors, waves and transcript of the seed SSI scenario in out/
#   make test        everything: cargo tests, every core's vectors in Icarus and
#                    Verilator, committed vectors == fresh ones, Verilator lint,
#                    every .gtkw layout opened in GTKWave (headless)
#   make vectors     regenerate vectors/<core>/ from the built-in scenarios
#   make sim CORE=ssi_master SIM=icarus|verilator [SCENARIO=ssi_seed_12bit] [WAVES=1]
#   make waves CORE=ssi_master [SCENARIO=ssi_seed_12bit]   open GTKWave on the saved layout
#   make synth       yosys + nextpnr-ice40 (hx8k) for every core: logic cells and Fmax
#   make bench       model vs Verilator vs Icarus cycles per second
#   make cosim       every core closed-loop against its encoder emulator (both simulators)
#   make soak        long runs: 100000 closed-loop transactions per core, the campaigns
#   make coverage    RTL line/branch/toggle coverage of every core, against the baseline
#   make mutate      mutation score of every core (long)
#   make deps        install Icarus, Verilator, yosys, nextpnr, GTKWave, sigrok-cli if missing

CORE ?= ssi_master
SIM ?= icarus
WAVES ?= 0
SCENARIO ?=
CARGO ?= cargo
TBGEN := target/release/tbgen

.PHONY: all demo vectors test deps build cargo-test hdl-test check-vectors check-gtkw lint sim waves synth bench cosim soak coverage mutate clean

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

# Every check, stage by stage with its wall time (scripts/test.sh): the
# cargo tests run beside the lint/replay/vector/GTKWave lane.
test:
	@scripts/test.sh

# The dev profile, so that arithmetic overflow panics in tests instead of
# wrapping silently as it would in release.
cargo-test:
	$(CARGO) test --workspace --locked

lint:
	@scripts/lint.sh

hdl-test:
	@scripts/regress.sh

check-vectors: build
	@scripts/check_vectors.sh

check-gtkw:
	@scripts/check_gtkw.sh

sim:
	@scripts/regress.sh --core $(CORE) --sim $(SIM) $(if $(SCENARIO),--scenario $(SCENARIO)) $(if $(filter 1,$(WAVES)),--waves)

waves:
	@scenario="$(SCENARIO)"; \
	 if [ -z "$$scenario" ]; then scenario=$$(ls vectors/$(CORE)/*.gtkw | head -n 1 | xargs basename | sed 's/\.gtkw$$//'); fi; \
	 cd vectors/$(CORE) && gtkwave "$$scenario.gtkw"

# Every core closed-loop against its encoder emulator (hdl/emu/, the cosim
# library), 1000 transactions per core in each simulator.
cosim:
	@scripts/cosim_regress.sh --transactions 1000

# Long runs kept out of make test: 100000 closed-loop transactions per core
# (Verilator) and the model's corruption campaigns, with their counts.
soak:
	@scripts/cosim_regress.sh --sim verilator --transactions 100000
	$(CARGO) test --release --locked -p model campaign -- --nocapture

# RTL line, branch and toggle coverage of every core over its vectors,
# against hdl/coverage/baseline.txt (make test reports it from its own
# Verilator replays).
coverage:
	@scripts/coverage.sh

# Mutants of each core replayed against its vectors (long: not in make test).
mutate:
	@status=0; for d in vectors/*/; do python3 scripts/mutate.py "$$(basename "$$d")" || status=1; done; exit $$status

synth:
	@scripts/synth.sh

bench: build
	@scripts/bench.sh

clean:
	rm -rf build out
