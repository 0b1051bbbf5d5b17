# Thin wrapper: every target first runs the bootstrap (installs missing Debian packages,
# configures and builds in Release), then does one thing.
BUILD ?= build
JOBS  ?= $(shell nproc)
FUZZ_RUNS ?= 1000000

.PHONY: all bootstrap test validate bench sanitize fuzz clean readme-figure paraview-figure

all: bootstrap

bootstrap:
	@RODLAB_BUILD_DIR=$(BUILD) ./scripts/bootstrap.sh

test: bootstrap
	cd $(BUILD) && ctest -LE validation --output-on-failure -j $(JOBS)

# the command line alone: validate runs nothing else (the tests and benchmarks are make test's
# and make bench's)
validate:
	@RODLAB_BUILD_DIR=$(BUILD) RODLAB_BUILD_TARGETS=rodlab ./scripts/bootstrap.sh
	$(BUILD)/bin/rodlab validate --quick --out out/validation

# every Google Benchmark program, then the first solve of `rodlab static` against the warm one
# for every statics scheme (bench/cold_static.py, docs/statics.md "Cold and warm solves")
bench: bootstrap
	@for b in $(BUILD)/bin/bench_*; do echo "== $$b"; $$b --benchmark_min_time=0.2 --benchmark_repetitions=5 --benchmark_report_aggregates_only=true; done
	@echo "== bench/cold_static.py"; /usr/bin/python3 bench/cold_static.py --build $(BUILD) --schemes all

# The unit suite under ASan + UBSan in build-asan/ (scripts/sanitize.sh).
sanitize: bootstrap
	./scripts/sanitize.sh

# libFuzzer on the scene loader and the --set overrides, FUZZ_RUNS inputs each, in build-fuzz/
# (scripts/fuzz.sh; installs clang and libclang-rt-dev when missing).
fuzz:
	@RODLAB_BUILD_DIR=$(BUILD) RODLAB_EXTRA_PACKAGES="clang libclang-rt-dev" ./scripts/bootstrap.sh
	./scripts/fuzz.sh $(FUZZ_RUNS)

# The README's figure (docs/figures/readme-cantilever.png): the Table 2.1 cantilever released
# straight under gravity, 0.5 s, drawn by `rodlab plot`.
readme-figure:
	@RODLAB_BUILD_DIR=$(BUILD) RODLAB_BUILD_TARGETS=rodlab ./scripts/bootstrap.sh
	@mkdir -p out docs/figures
	$(BUILD)/bin/rodlab dynamic scenes/cantilever-gravity.yaml --t-end 0.5 --quiet --out out/readme-cantilever.json
	$(BUILD)/bin/rodlab plot out/readme-cantilever.json --out docs/figures/readme-cantilever.png

# docs/figures/paraview-swing.png: the same cantilever's first down-swing (0.12 s) written with
# --vtk and rendered headless by ParaView's pvpython (scripts/paraview_figure.py) under a virtual
# X server. Needs Debian's paraview, python3-paraview and xvfb (a large install, so not in the
# bootstrap): apt-get install paraview python3-paraview xvfb.
paraview-figure:
	@command -v pvpython >/dev/null && command -v xvfb-run >/dev/null || \
	  { echo "make paraview-figure: needs pvpython and xvfb-run: apt-get install paraview python3-paraview xvfb" >&2; exit 2; }
	@RODLAB_BUILD_DIR=$(BUILD) RODLAB_BUILD_TARGETS=rodlab ./scripts/bootstrap.sh
	@rm -rf out/paraview-swing && mkdir -p out docs/figures
	$(BUILD)/bin/rodlab dynamic scenes/cantilever-gravity.yaml --t-end 0.12 --nodes 20 --output-every 5 --quiet --vtk out/paraview-swing
	xvfb-run -a -s "-screen 0 1600x1200x24" pvpython scripts/paraview_figure.py out/paraview-swing/rod.pvd docs/figures/paraview-swing.png

clean:
	rm -rf $(BUILD) build-asan build-fuzz out
