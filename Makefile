# frictiondisk: set-up, demo, tests, benchmarks and lint.
#
#   make demo    create .venv, install from the lock file, locate mu* along the demo lines
#                (the pin, and the paper's disk from rest), print the mu* tables, draw the
#                mu* lines and one orbit, show where the outputs are
#   make install create .venv, install from the lock file, compile the numba kernel once
#   make test    create .venv if needed, install from the lock file, run the test suite
#   make lock    refresh requirements/lock.txt (the newest versions pyproject.toml allows;
#                LOCK_ARGS= keeps the pinned versions and only adds what is new)
#   make bench   the performance benchmarks (benchmarks/, docs/benchmarks.md): each measures
#                its baseline in the same run, prints ratios and writes its numbers to
#                out/bench/<name>.json (benchmarks/harness.py): kernel, campaign and
#                contact-layout benchmarks (bench_layouts: cost per step against N, arrow vs
#                dense LU), runs per mu* (bench_runs: the search against plain bisection),
#                start-up (bench_startup: warm simulate, the fixed cost of run), basin
#                campaigns per run (bench_basin), the six figure campaigns one by one against
#                one run of all six (bench_together; BENCH_TOGETHER_ARGS=--quick for a smoke
#                check), the strong-scaling table (BENCH_SCALING_ARGS=--full for the
#                campaign files as is) and the engine at the kernel's pace (bench_engine:
#                efficiency and cost per run of scans of 40 to 4 000 short runs and a basin
#                of 10 000; BENCH_ENGINE_ARGS=--big adds the 40 000-run scan)
#   make study-wellposed  the well-posedness study (docs/wellposed.md) into out/wellposed/:
#                500 scenes, about 4 hours on 2 idle cores, resumable (STUDY_ARGS= adds
#                options, e.g. STUDY_ARGS="--seeds 1 --scenes 10"); then generator 2 (issue 50)
#                into out/wellposed2/: 200 scenes (seeds 1-4)
#   make study-error-model  regenerate frictiondisk/model/numerics_error.csv (the error model
#                of numerics auto, docs/accuracy.md) from out/error_model/; hours
#   make study-brake, study-layouts, study-corotation  the braked disk's studies
#                (docs/brake.md, docs/layouts.md, docs/user-guide.md section 3)
#   make figures run the paper's figure campaigns (campaigns/fig*.yaml, and the traced Fig 11)
#                into out/figures/
#                and draw out/figures/<name>.png and .pdf (the tracked tree stays clean)
#   make gallery draw every PNG under figures/ again from this code (frictiondisk/cli/gallery.py:
#                the figure campaigns, the basin campaigns, the brake and corotation studies,
#                the accuracy studies; commit them). About 7 minutes on 2 cores
#                from nothing; RUNS=DIR starts from finished run folders DIR/<campaign>/
#                (`frictiondisk run campaigns/X.yaml -o DIR/X`), rerunning only what this
#                numerics version has not journaled; GALLERY_ARGS="--only basin" picks
#   make basin-figures  run the basin campaigns (campaigns/basin_*.yaml) into out/basin/
#                and draw figures/basin_*.png (docs/user-guide.md, "Basin stability")
#   make docs    build the documentation site (docs/*.md, the API reference from the public
#                API's docstrings, the CLI reference from the click commands) into
#                build/docs/html with Sphinx, warnings as errors; runs no campaign
#   make lint    ruff check + ruff format --check
#   make clean   remove outputs and caches (keeps .venv; `make distclean` removes it too)

VENV ?= .venv
PYTHON ?= python3
# The suite runs on two processes (pytest-xdist; 2 cores is what CI has). worksteal: the
# few long tests (cross-checks against scipy, exact Coulomb watches) do not hold up a worker
# while the other has finished its share. PYTEST_ARGS= runs it in one process.
PYTEST_ARGS ?= -n 2 --dist worksteal
BENCH_SCALING_ARGS ?= --quick
BENCH_TOGETHER_ARGS ?= --repeat 2
STUDY_ARGS ?=
RUNS ?=
GALLERY_ARGS ?=

BIN := $(VENV)/bin
STAMP := $(VENV)/.frictiondisk-installed
LINT_PATHS := frictiondisk tests benchmarks

DEMO_FOLDER := out/demo
DEMO_SCENE := campaigns/demo_pin.yaml
DEMO_DIR := $(DEMO_FOLDER)/orbit
DEMO_NC := $(DEMO_DIR)/trajectory.nc
DEMO_PNG := $(DEMO_DIR)/orbit.png
DEMO_JSON := $(DEMO_DIR)/summary.json
DEMO_CAMPAIGN := campaigns/demo_line.yaml
DEMO_CAMPAIGN_DIR := $(DEMO_FOLDER)/demo_line
DEMO_LINE_PNG := $(DEMO_CAMPAIGN_DIR)/mu_star.png
DEMO_DISK_CAMPAIGN := campaigns/demo_disk_line.yaml
DEMO_DISK_DIR := $(DEMO_FOLDER)/demo_disk_line
DEMO_DISK_PNG := $(DEMO_DISK_DIR)/mu_star.png
LOCK := requirements/lock.txt
LOCK_ARGS ?= --upgrade

.PHONY: all install lock demo test bench figures gallery basin-figures docs lint clean distclean \
	study-wellposed study-error-model study-brake study-layouts study-corotation

all: test

# (Re)install whenever pyproject.toml or the lock file changes; an existing .venv is reused,
# never recreated. Every dependency comes from the lock file (exact versions and hashes);
# the project itself is installed without resolving dependencies again. Then the numba
# kernel is compiled into its cache (frictiondisk/kernel/__pycache__), so that the first
# campaign or simulate loads it instead of compiling it (docs/benchmarks.md, compile).
$(STAMP): pyproject.toml $(LOCK)
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -r $(LOCK)
	$(BIN)/python -m pip install --no-deps -e .
	$(BIN)/python -c "from frictiondisk.engine.worker import warm_up; warm_up()"
	touch $@

install: $(STAMP)

# The lock file: runtime + test, dashboard and docs extras, resolved for CPython 3.11 on linux x86_64 by uv
# (installed into .venv for this purpose only). Commit the result.
lock:
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q uv
	$(BIN)/uv pip compile --quiet pyproject.toml --extra test --extra dashboard --extra docs $(LOCK_ARGS) --generate-hashes \
		--python-version 3.11 --python-platform x86_64-unknown-linux-gnu -o $(LOCK)

# The main job: locate the jump mu* along two lines of axes offsets, the pin's and the
# disk's, in one run (each campaign into out/demo/<name>/; resumes if interrupted), then
# one orbit of the demo scene.
demo: $(STAMP)
	$(BIN)/frictiondisk run $(DEMO_CAMPAIGN) $(DEMO_DISK_CAMPAIGN) -o $(DEMO_FOLDER)
	$(BIN)/frictiondisk plot $(DEMO_CAMPAIGN_DIR) -o $(DEMO_LINE_PNG)
	$(BIN)/frictiondisk plot $(DEMO_DISK_DIR) -o $(DEMO_DISK_PNG)
	@mkdir -p $(DEMO_DIR)
	$(BIN)/frictiondisk simulate $(DEMO_SCENE) --json -o $(DEMO_NC) --plot $(DEMO_PNG) > $(DEMO_JSON)
	@echo ""
	@echo "Demo finished. Outputs:"
	@echo "  jump mu* along x_ms (netCDF): $(abspath $(DEMO_CAMPAIGN_DIR)/results.nc)"
	@echo "  every run of it (netCDF):     $(abspath $(DEMO_CAMPAIGN_DIR)/runs.nc)"
	@echo "  the mu* line (PNG):           $(abspath $(DEMO_LINE_PNG))"
	@echo "  disk from rest, mu* (netCDF): $(abspath $(DEMO_DISK_DIR)/results.nc)"
	@echo "  disk from rest, mu* (PNG):    $(abspath $(DEMO_DISK_PNG))"
	@echo "  one run, summary (JSON):      $(abspath $(DEMO_JSON))"
	@echo "  one run, trajectory (netCDF): $(abspath $(DEMO_NC))"
	@echo "  one run, orbit plot (PNG):    $(abspath $(DEMO_PNG))"

test: $(STAMP)
	$(BIN)/python -m pytest $(PYTEST_ARGS)

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_kernel.py
	$(BIN)/python benchmarks/bench_campaign.py
	$(BIN)/python benchmarks/bench_layouts.py
	$(BIN)/python benchmarks/bench_runs.py
	$(BIN)/python benchmarks/bench_startup.py
	$(BIN)/python benchmarks/bench_basin.py
	$(BIN)/python benchmarks/bench_together.py $(BENCH_TOGETHER_ARGS)
	$(BIN)/python benchmarks/bench_scaling.py $(BENCH_SCALING_ARGS)
	$(BIN)/python benchmarks/bench_engine.py $(BENCH_ENGINE_ARGS)

figures: $(STAMP)
	$(BIN)/python -m frictiondisk.cli.figure_campaigns --campaigns campaigns --out out/figures --figures out/figures

gallery: $(STAMP)
	$(BIN)/python -m frictiondisk.cli.gallery --out out/gallery --figures figures \
		$(if $(RUNS),--runs $(RUNS)) $(GALLERY_ARGS)

basin-figures: $(STAMP)
	$(BIN)/python -m frictiondisk.studies.basin --out out/basin --figures figures

# The studies (frictiondisk/studies/): each runs its campaigns on the engine into out/<study>/
# and resumes from their journals when run again.
study-wellposed: $(STAMP)
	$(BIN)/python -m frictiondisk.studies.wellposed -o out/wellposed $(STUDY_ARGS); \
	first=$$?; \
	$(BIN)/python -m frictiondisk.studies.wellposed -o out/wellposed2 --generator 2 \
		--seeds 1-4 $(STUDY_ARGS); \
	exit $$(( first | $$? ))

study-error-model: $(STAMP)
	$(BIN)/python -m frictiondisk.studies.error_model -o out/error_model --write

study-brake: $(STAMP)
	$(BIN)/python -m frictiondisk.studies.brake -o out/brake --figures figures

study-layouts: $(STAMP)
	$(BIN)/python -m frictiondisk.studies.layouts -o out/study_layouts

study-corotation: $(STAMP)
	$(BIN)/python -m frictiondisk.studies.corotation -o out/corotation --figure figures/brake_drift.png

# The documentation site: -W turns every warning (a broken link, a page outside the
# table of contents, a docstring that does not parse) into an error; -E rereads every page.
DOCS_OUT := build/docs/html
docs: $(STAMP)
	$(BIN)/python -m sphinx -b html -W --keep-going -E docs $(DOCS_OUT)
	@echo "Documentation site: $(abspath $(DOCS_OUT))/index.html"

lint: $(STAMP)
	$(BIN)/ruff check $(LINT_PATHS)
	$(BIN)/ruff format --check $(LINT_PATHS)

clean:
	rm -rf out .pytest_cache .ruff_cache .hypothesis build dist *.egg-info
	find frictiondisk tests benchmarks -type d -name __pycache__ -prune -exec rm -rf {} +
	find frictiondisk -type f \( -name '*.nbi' -o -name '*.nbc' \) -delete

distclean: clean
	rm -rf $(VENV)
