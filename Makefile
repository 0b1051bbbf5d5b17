# Thin wrapper: every target first runs the bootstrap (installs missing Debian packages,
# configures and builds in Release), then does one thing.
BUILD ?= build
JOBS  ?= $(shell nproc)

.PHONY: all bootstrap test validate bench clean

all: bootstrap

bootstrap:
	@RODLAB_BUILD_DIR=$(BUILD) ./scripts/bootstrap.sh

test: bootstrap
	cd $(BUILD) && ctest -LE validation --output-on-failure -j $(JOBS)

validate: bootstrap
	$(BUILD)/bin/rodlab validate --quick --out out/validation

bench: bootstrap
	@for b in $(BUILD)/bin/bench_*; do echo "== $$b"; $$b --benchmark_min_time=0.2 --benchmark_repetitions=5 --benchmark_report_aggregates_only=true; done

clean:
	rm -rf $(BUILD) out
