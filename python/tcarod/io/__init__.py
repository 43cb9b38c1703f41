"""Input and output: robot designs as TOML files (:mod:`tcarod.io.design`) and
results as JSON documents (:mod:`tcarod.io.results`)."""
