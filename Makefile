# Developer tasks. `make test` runs the same commands as the README's test line
# (which CI runs through .ci/run); run `make install` first.
.PHONY: install test lint bench docs wheel clean

PYTHON ?= python

install:
	$(PYTHON) -m pip install -e '.[test]'

test:
	cargo test --release
	$(PYTHON) -m pytest
	$(PYTHON) -m mypy
	$(PYTHON) -m mypy.stubtest tcarod._core --allowlist tests/stubtest_allowlist.txt
	$(PYTHON) -m mkdocs build --strict

lint:
	cargo fmt --check
	cargo clippy --all-targets -- -D warnings
	cargo clippy --features python -- -D warnings
	$(PYTHON) -m ruff check .
	$(PYTHON) -m ruff format --check .

bench:
	cargo bench
	tcarod bench

# The crate docs (no warnings allowed) and the site; the build hook copies the
# crate docs into site/rust/.
docs:
	RUSTDOCFLAGS="-D warnings" cargo doc --no-deps
	$(PYTHON) -m mkdocs build --strict

# The portable wheel in dist/: manylinux2014 abi3 via zig, auditwheel, smoke
# test in a fresh venv without Rust (stage 2 of .ci/run).
wheel:
	bash .ci/run --wheel-only

clean:
	rm -rf dist site docs/figures docs/gallery
