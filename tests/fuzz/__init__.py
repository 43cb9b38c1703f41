"""tcarod's own fuzz suite: hypothesis strategies for every public
entry point (:mod:`fuzz.strategies`), one outcome classifier and a worker
process (:mod:`fuzz.harness`). The quick profile is ``tests/test_fuzz.py``;
the long profile is ``benches/fuzz_long.py``."""
