# Developer tasks. `make test` is the README's test command, the one line CI
# (.ci/run) runs: the editable install with the test extra, the linters, every
# test, the type checks and the strict docs build, each step timed.
#
# Tests, lint and the editable install build with the `fast` cargo profile
# (Cargo.toml: release opt-level, no LTO, parallel codegen); the wheel
# (`make wheel`, CI's packaging step) and the benchmarks keep full optimisation.
.PHONY: install test lint rustdoc test-rust test-python typecheck site bench perf-report docs wheel clean

PYTHON ?= python
PROFILE ?= fast
# The notebooks executed and the figures drawn by the tests, reused by the docs
# build of the same `make test` run (docs/_hooks.py) instead of being made twice.
ARTIFACTS := $(CURDIR)/build/test-artifacts
STEP := bash .ci/step

install:
	MATURIN_PEP517_ARGS="--profile $(PROFILE)" $(PYTHON) -m pip install -e '.[test]'

test: export TCAROD_TEST_ARTIFACTS := $(ARTIFACTS)
test: export STEP_TIMES := $(ARTIFACTS)/step-times.txt
test:
	@rm -rf $(ARTIFACTS) && mkdir -p $(ARTIFACTS)
	@$(STEP) install $(MAKE) --no-print-directory install
	@$(STEP) lint $(MAKE) --no-print-directory lint
	@$(STEP) rustdoc $(MAKE) --no-print-directory rustdoc
	@$(STEP) test-rust $(MAKE) --no-print-directory test-rust
	@$(STEP) test-python $(MAKE) --no-print-directory test-python
	@$(STEP) typecheck $(MAKE) --no-print-directory typecheck
	@$(STEP) site $(MAKE) --no-print-directory site
	@echo "=== make test: every step passed"
	@awk '{ total += $$2; printf "    %-12s %5d s\n", $$1, $$2 } END { printf "    %-12s %5d s\n", "total", total }' $(STEP_TIMES)

# rustfmt, clippy once over every target with every feature (the pyo3-free
# core and the `python` bindings), ruff.
lint:
	cargo fmt --check
	cargo clippy --all-targets --all-features -- -D warnings
	$(PYTHON) -m ruff check .
	$(PYTHON) -m ruff format --check .

rustdoc:
	RUSTDOCFLAGS="-D warnings" cargo doc --no-deps

test-rust:
	cargo test --profile $(PROFILE)

# Two pytest workers (pytest-xdist, one per core); the Dask tests share one
# local cluster and run on one worker (tests/conftest.py).
test-python:
	$(PYTHON) -m pytest -n 2 --dist loadgroup

typecheck:
	$(PYTHON) -m mypy
	$(PYTHON) -m mypy.stubtest tcarod._core --allowlist tests/stubtest_allowlist.txt

site:
	$(PYTHON) -m mkdocs build --strict

bench:
	cargo bench
	tcarod bench

# docs/performance.md, written from scratch from fresh measurements (tcarod
# bench, criterion, the design benches; a few minutes plus the bench build).
perf-report:
	$(PYTHON) benches/report.py

# The crate docs (no warnings allowed) and the site; the build hook copies the
# crate docs into site/rust/.
docs: rustdoc site

# The portable wheel in dist/: manylinux2014 abi3 via zig, auditwheel, smoke
# test in a fresh venv without Rust (stage 2 of .ci/run).
wheel:
	bash .ci/run --wheel-only

clean:
	rm -rf build dist site docs/figures docs/gallery
