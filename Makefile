# The README's two commands: `make run` (set up, run the main job) and `make test` (set up, run every test).
# Setup is a virtual environment in .venv with pipelay built by maturin (release) and its dependencies.
# `make docs` builds the documentation site into site/ (MkDocs, strict: a broken link or reference fails).
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
OUT ?= output
SOURCES := $(shell find crates python -name '*.rs' -o -name '*.py' -o -name '*.pyi' -o -name Cargo.toml) \
	Cargo.toml Cargo.lock pyproject.toml

.PHONY: run test lint bench docs

$(STAMP): $(SOURCES)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --disable-pip-version-check "maturin>=1.7,<2"
	VIRTUAL_ENV=$(abspath $(VENV)) $(BIN)/maturin develop --release --extras test,docs
	touch $@

run: $(STAMP)
	$(BIN)/python examples/jensen2009.py --out $(OUT)
	$(BIN)/python examples/hanging_pipe.py --out $(OUT)

test: $(STAMP)
	cargo test --workspace --release
	$(BIN)/python -m pytest

lint: $(STAMP)
	cargo fmt --all --check
	cargo clippy --workspace --all-targets --release -- -D warnings
	$(BIN)/ruff check python tests examples benches scripts docs/hooks
	$(BIN)/ruff format --check python tests examples benches scripts docs/hooks
	$(BIN)/python -m mypy.stubtest pipelay._core --ignore-disjoint-bases

docs: $(STAMP)
	$(BIN)/mkdocs build --strict

bench: $(STAMP)
	$(BIN)/python benches/static_hanging.py
	$(BIN)/python benches/dynamic_step_cost.py
	$(BIN)/python benches/jensen2009_speed.py
	$(BIN)/python benches/validation_statics.py
	$(BIN)/python benches/seabed_cost.py
	$(BIN)/python benches/seabed_statics.py
	$(BIN)/python benches/lay_cost.py
	$(BIN)/python benches/full_cost.py
	$(BIN)/python benches/pay_out_rollers.py
	$(BIN)/python benches/memory.py
	$(BIN)/python benches/sea_cost.py
	$(BIN)/python benches/storm.py
	$(BIN)/python benches/surface_ringing.py
	$(BIN)/python benches/moordyn_race.py
	$(BIN)/python benches/moordyn_wave_race.py
