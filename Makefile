# The tortuosity package: a map from paper.nw and the data to results, figures and the report.
#
#   make              tangle paper.nw and build bin/tortuosity
#   make check        unit tests (from paper.nw) and end-to-end checks (tests/)
#   make reproduce    data -> results/ -> figures/ -> build/paper.pdf
#   make report       build/paper.pdf (runs whatever results it needs)
#   make paper        build/paper.pdf from the committed results/ and figures/ (no data needed)
#   make bench        timing of the full BraVa set
#   make check-sanitize   the tests under AddressSanitizer and UndefinedBehaviorSanitizer
#   make fuzz         libFuzzer on each reader (FUZZ_SECONDS per reader, default 150)
#   make lint         chunk roots of paper.nw against the list below
#   make clean
#
# Real data are read from DATA_DIR (never copied); data/manifest.tsv lists them.

SHELL := /bin/bash
.SHELLFLAGS := -o pipefail -ec
.DELETE_ON_ERROR:
.SUFFIXES:
MAKEFLAGS += --no-builtin-rules

DATA_DIR ?= ../shared/data
export SOURCE_DATE_EPOCH ?= 1795305600

CC      ?= cc
CFLAGS  ?= -O3
CFLAGS  += -std=c11 -D_GNU_SOURCE -Wall -Wextra -fopenmp
LDLIBS  := -lgsl -lgslcblas -lm

# ---------------------------------------------------------------- tools
# Debian packages that provide what each stage needs; installed on demand.
BUILD_PACKAGES  := make gcc libc6-dev noweb libgsl-dev
REPORT_PACKAGES := gnuplot-nox r-base-core texlive-latex-base texlive-latex-recommended \
                   texlive-fonts-recommended lmodern
BUILD_TOOLS  := build/.tools-build
REPORT_TOOLS := build/.tools-report
TEXMF        := /usr/share/texlive/texmf-dist/tex/latex

# $(call ensure_packages,PACKAGES,COMMANDS,FILES): install PACKAGES unless every command and file exists.
define ensure_packages
missing=; for t in $(2); do command -v $$t >/dev/null || missing="$$missing $$t"; done; \
for f in $(3); do [ -e $$f ] || missing="$$missing $$f"; done; \
if [ -n "$$missing" ]; then \
  if [ "$$(id -u)" = 0 ]; then \
    echo "missing:$$missing; installing: $(1)"; \
    apt-get update -qq; \
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $(1) >/dev/null; \
  else \
    echo "missing:$$missing. Install with:"; \
    echo "  sudo apt-get install $(1)"; \
    exit 1; \
  fi; \
fi
endef

$(BUILD_TOOLS):
	@mkdir -p build
	@$(call ensure_packages,$(BUILD_PACKAGES),notangle cpif noroots $(CC),/usr/include/gsl/gsl_bspline.h)
	@touch $@

$(REPORT_TOOLS): | $(BUILD_TOOLS)
	@$(call ensure_packages,$(REPORT_PACKAGES),gnuplot Rscript pdflatex noweave,$(TEXMF)/booktabs/booktabs.sty)
	@touch $@

# ---------------------------------------------------------------- tangle
MODULES := vessel readers pspline stencil metrics frenet phantom pipeline
HEADERS := $(addprefix build/src/,geom.h $(addsuffix .h,$(MODULES)))
LIB_OBJ := $(addprefix build/obj/,$(addsuffix .o,$(MODULES)))
C_ROOTS := $(addprefix src/,geom.h $(addsuffix .h,$(MODULES)) $(addsuffix .c,$(MODULES)) \
             tortuosity.c unit-tests.c fuzz-readers.c)
SCRIPTS := scripts/analysis.R scripts/recon-error.gp scripts/percent-shift.gp scripts/soa-acct.gp \
           scripts/profile.gp
ROOTS   := $(C_ROOTS) $(SCRIPTS)
.SECONDARY: $(addprefix build/,$(ROOTS))   # tangled files are kept, so cpif can compare

build/src/%: paper.nw | $(BUILD_TOOLS)
	@mkdir -p $(dir $@)
	notangle -L -R'src/$*' paper.nw | cpif $@

build/scripts/%: paper.nw | $(BUILD_TOOLS)
	@mkdir -p $(dir $@)
	notangle -R'scripts/$*' paper.nw | cpif $@

# Objects also depend on the Makefile, so a change of flags rebuilds them.
build/obj/%.o: build/src/%.c $(HEADERS) Makefile
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Ibuild/src -c -o $@ $<

# ---------------------------------------------------------------- programs
.PHONY: all
all: bin/tortuosity

bin/tortuosity: build/obj/tortuosity.o $(LIB_OBJ)
	@mkdir -p bin
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

build/unit-tests: build/obj/unit-tests.o $(LIB_OBJ)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

# ---------------------------------------------------------------- tests
.PHONY: check
check: build/unit-tests bin/tortuosity
	@echo "== unit tests (paper.nw)"
	@./build/unit-tests | tee build/unit-tests.log
	@echo "== end-to-end checks (tests/)"
	@DATA_DIR='$(DATA_DIR)' bash tests/end-to-end.sh bin/tortuosity | tee build/end-to-end.log
	@awk '/^(e2e: )?[0-9]+ passed, [0-9]+ failed$$/ { sub(/^e2e: /, ""); p += $$1; f += $$3 } \
	      END { printf "check: %d passed, %d failed\n", p, f; exit f > 0 }' build/unit-tests.log build/end-to-end.log

# The same suite with AddressSanitizer and UndefinedBehaviorSanitizer; any report is fatal.
SAN_FLAGS := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all
SAN_OBJ   := $(addprefix build/sanitize/,$(addsuffix .o,$(MODULES)))

build/sanitize/%.o: build/src/%.c $(HEADERS) Makefile
	@mkdir -p $(dir $@)
	$(CC) $(filter-out -O%,$(CFLAGS)) $(SAN_FLAGS) -Ibuild/src -c -o $@ $<
build/sanitize/unit-tests: build/sanitize/unit-tests.o $(SAN_OBJ)
	$(CC) $(filter-out -O%,$(CFLAGS)) $(SAN_FLAGS) -o $@ $^ $(LDLIBS)
build/sanitize/tortuosity: build/sanitize/tortuosity.o $(SAN_OBJ)
	$(CC) $(filter-out -O%,$(CFLAGS)) $(SAN_FLAGS) -o $@ $^ $(LDLIBS)

.PHONY: check-sanitize
check-sanitize: build/sanitize/unit-tests build/sanitize/tortuosity
	@echo "== unit tests, sanitized"
	@ASAN_OPTIONS=detect_leaks=1 ./build/sanitize/unit-tests | tee build/sanitize/unit-tests.log
	@echo "== end-to-end checks, sanitized"
	@ASAN_OPTIONS=detect_leaks=1 DATA_DIR='$(DATA_DIR)' bash tests/end-to-end.sh build/sanitize/tortuosity \
	  | tee build/sanitize/end-to-end.log
	@awk '/^(e2e: )?[0-9]+ passed, [0-9]+ failed$$/ { sub(/^e2e: /, ""); p += $$1; f += $$3 } \
	      END { printf "check-sanitize: %d passed, %d failed\n", p, f; exit f > 0 }' \
	      build/sanitize/unit-tests.log build/sanitize/end-to-end.log

# ---------------------------------------------------------------- fuzzing
# One libFuzzer harness per reader, seeded from the real files; crashes land in build/fuzz/.
FUZZ_SECONDS ?= 150
FUZZ_FORMATS := text csv swc angicart
FUZZ_TOOLS   := build/.tools-fuzz
LIB_SOURCES  := $(addprefix build/src/,$(addsuffix .c,$(MODULES)))

$(FUZZ_TOOLS): | $(BUILD_TOOLS)
	@$(call ensure_packages,clang libclang-rt-14-dev,clang,)
	@touch $@

build/fuzz/fuzz-%: build/src/fuzz-readers.c $(LIB_SOURCES) $(HEADERS) | $(FUZZ_TOOLS)
	@mkdir -p $(dir $@)
	clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -D_GNU_SOURCE \
	  -DFUZZ_FORMAT=FORMAT_$(shell echo $* | tr a-z A-Z) -Ibuild/src -o $@ $< $(LIB_SOURCES) $(LDLIBS)

build/fuzz/corpus-%/.seeded: data/manifest.tsv bin/tortuosity
	@mkdir -p $(dir $@)
	@shopt -s nullglob; n=0; \
	case $* in \
	  swc) files=('$(DATA_DIR)'/brava-*/*.swc '$(DATA_DIR)'/brava-*/*/*.swc '$(DATA_DIR)'/brava-*/*/*/*.swc);; \
	  csv) files=('$(DATA_DIR)'/*/*.csv);; \
	  angicart) files=('$(DATA_DIR)'/*/*.dat);; \
	  text) ./bin/tortuosity phantom --shape salkowski --sigma 0.01 >$(dir $@)/salkowski.txt; \
	        ./bin/tortuosity phantom --shape helix --count 3 --points 12 >$(dir $@)/helices.txt; files=();; \
	esac; \
	for f in "$${files[@]:0:12}"; do head -c 8000 "$$f" >$(dir $@)/seed-$$n; n=$$((n + 1)); done; \
	touch $@

.PHONY: fuzz
fuzz: $(addprefix build/fuzz/fuzz-,$(FUZZ_FORMATS)) $(foreach f,$(FUZZ_FORMATS),build/fuzz/corpus-$(f)/.seeded)
	@for f in $(FUZZ_FORMATS); do \
	  echo "fuzz $$f for $(FUZZ_SECONDS) s"; \
	  ./build/fuzz/fuzz-$$f -max_total_time=$(FUZZ_SECONDS) -max_len=16384 -print_final_stats=1 \
	    -artifact_prefix=build/fuzz/crash-$$f- build/fuzz/corpus-$$f >build/fuzz/$$f.log 2>&1 \
	    || { tail -40 build/fuzz/$$f.log; echo "fuzz $$f: crash, input saved in build/fuzz/"; exit 1; }; \
	  grep -E 'stat::number_of_executed_units|stat::peak_rss_mb' build/fuzz/$$f.log | sed "s/^/fuzz $$f: /"; \
	done

.PHONY: lint
lint: | $(BUILD_TOOLS)
	@diff <(noroots paper.nw | sed 's/^<<\(.*\)>>$$/\1/' | sort) <(printf '%s\n' $(ROOTS) | sort) \
	  && echo "lint: chunk roots match the Makefile" \
	  || { echo "lint: roots of paper.nw ('<') differ from the Makefile ('>'); a misspelled chunk name?"; exit 1; }

# ---------------------------------------------------------------- data -> results
# Per-vessel results (large, not committed): every dataset of the manifest at every rate,
# measured four ways. Each file is written atomically by tortuosity -o.
DATASETS := $(shell awk -F'\t' 'NR > 1 { print $$1 }' data/manifest.tsv)
RATES    := 1,2,10,100
VARIANTS := backward-euler rotation bishop filtered
RUNS     := $(foreach v,$(VARIANTS),$(foreach d,$(DATASETS),build/results/$(v)/$(d).tsv))

# In a recipe for build/results/.../METHOD/DATASET.tsv: set shell variables method, dataset and
# files (the dataset's files under DATA_DIR, from the manifest), or stop when there are none.
define dataset_files
method=$(patsubst %/,%,$(dir $*)); dataset=$(notdir $*); \
pattern=$$(awk -F'\t' -v d="$$dataset" '$$1 == d { print $$2 }' data/manifest.tsv); \
shopt -s nullglob; files=('$(DATA_DIR)'/$$pattern); \
if [ $${#files[@]} -eq 0 ]; then \
  echo "$(DATA_DIR)/$$pattern: no such files; give the data directory as DATA_DIR=..." >&2; exit 2; fi
endef

$(RUNS): build/results/%.tsv: data/manifest.tsv bin/tortuosity
	@mkdir -p $(@D)
	@$(dataset_files); \
	case $$method in rotation|bishop) opts="--integrator $$method";; filtered) opts="--filter";; *) opts="";; esac; \
	echo "measure $$dataset ($$method): $${#files[@]} file(s)"; \
	./bin/tortuosity metrics -q --rates $(RATES) $$opts -o $@ "$${files[@]}"

# The smallest sufficient rate per vessel, for the datasets with radii, three integrators.
RADII_DATASETS := $(shell awk -F'\t' 'NR > 1 && $$5 != "none" { print $$1 }' data/manifest.tsv)
INTEGRATORS    := backward-euler rotation bishop
SUFFICIENT     := $(foreach i,$(INTEGRATORS),$(foreach d,$(RADII_DATASETS),build/results/sufficient/$(i)/$(d).tsv))

$(SUFFICIENT): build/results/sufficient/%.tsv: data/manifest.tsv bin/tortuosity
	@mkdir -p $(@D)
	@$(dataset_files); \
	echo "sufficient rate: $$dataset ($$method)"; \
	./bin/tortuosity sufficient -q --integrator $$method -o $@ "$${files[@]}"

# Phantoms: noise-free, and 100 with sigma = 0.01 mm (seed 1), three integrators.
build/results/phantoms.tsv: bin/tortuosity
	@mkdir -p $(@D)
	@tmp=$$(mktemp -d); trap 'rm -rf "$$tmp"' EXIT; \
	printf 'shape\tnoise\tintegrator\t' >$@.tmp; \
	./bin/tortuosity phantom | ./bin/tortuosity metrics -q - | head -1 >>$@.tmp; \
	for shape in circle helix salkowski; do \
	  ./bin/tortuosity phantom --shape $$shape >$$tmp/clean.txt; \
	  ./bin/tortuosity phantom --shape $$shape --sigma 0.01 --count 100 --seed 1 >$$tmp/noisy.txt; \
	  for noise in clean noisy; do for integ in backward-euler rotation bishop; do \
	    ./bin/tortuosity metrics -q --rates $(RATES) --integrator $$integ $$tmp/$$noise.txt \
	      | tail -n +2 | sed "s|^$$tmp/|$$shape\t$$noise\t$$integ\t|" >>$@.tmp; \
	  done; done; \
	done; mv $@.tmp $@

build/results/phantom-truth.tsv: bin/tortuosity
	@mkdir -p $(@D)
	@{ printf 'shape\t'; ./bin/tortuosity phantom --truth | head -1; \
	  for shape in circle helix salkowski; do \
	    printf '%s\t' $$shape; ./bin/tortuosity phantom --shape $$shape --truth | tail -1; done; } >$@.tmp
	@mv $@.tmp $@

# One coronary centerline, sample by sample, for the profile figure.
PROFILE_INPUT = $(DATA_DIR)/fdenz-coronary/centerlines.lines.csv
build/results/profile-%-rotation.tsv: bin/tortuosity
	@mkdir -p $(@D)
	./bin/tortuosity profile -q --rate $* --vessel 0 --integrator rotation -o $@ '$(PROFILE_INPUT)'
build/results/profile-%.tsv: bin/tortuosity
	@mkdir -p $(@D)
	./bin/tortuosity profile -q --rate $* --vessel 0 -o $@ '$(PROFILE_INPUT)'

# ---------------------------------------------------------------- results -> tables
# Small summaries, committed. R writes into a scratch folder; files are moved into place.
RESULT_TABLES := results/phantom-table.tex results/recon-table.tex results/soa-acct-table.tex \
                 results/correlation.tex results/sufficient-table.tex results/numbers.tex
RESULT_TSVS   := results/phantom-salkowski.tsv results/recon-error.tsv results/percent-shift.tsv \
                 results/soa-acct.tsv results/correlation.tsv results/sufficient.tsv
SOA_POINTS    := build/results/soa-acct-points.tsv

$(RESULT_TABLES) $(RESULT_TSVS) $(SOA_POINTS) &: build/scripts/analysis.R $(RUNS) $(SUFFICIENT) \
    build/results/phantoms.tsv build/results/phantom-truth.tsv | $(REPORT_TOOLS)
	@rm -rf build/results/summary.tmp && mkdir -p build/results/summary.tmp results
	Rscript --vanilla build/scripts/analysis.R build/results build/results/summary.tmp $(SOA_POINTS).tmp \
	  '$(RADII_DATASETS)'
	@mv $(SOA_POINTS).tmp $(SOA_POINTS)
	@for f in $(RESULT_TABLES) $(RESULT_TSVS); do mv build/results/summary.tmp/$$(basename $$f) $$f; done

# ---------------------------------------------------------------- tables -> figures
FIGURES := figures/recon-error.pdf figures/percent-shift.pdf figures/soa-acct.pdf figures/profile.pdf
GNUPLOT  = gnuplot -e "datasets='$(DATASETS)'; outfile='$@.tmp'"
# cairo 1.16 stamps the wall-clock time; replace it (same length) so figures are byte-identical.
PDF_DATE = $(shell date -u -d @$(SOURCE_DATE_EPOCH) +%Y%m%d%H%M%S)
FIX_DATE = perl -0777 -pi -e 's{/CreationDate \(D:\d{14}Z\)}{/CreationDate (D:$(PDF_DATE)Z)}' $@.tmp

figures/recon-error.pdf: build/scripts/recon-error.gp results/recon-error.tsv | $(REPORT_TOOLS)
	@mkdir -p figures
	$(GNUPLOT) -e "infile='results/recon-error.tsv'" $< && $(FIX_DATE) && mv $@.tmp $@
figures/percent-shift.pdf: build/scripts/percent-shift.gp results/percent-shift.tsv | $(REPORT_TOOLS)
	@mkdir -p figures
	$(GNUPLOT) -e "infile='results/percent-shift.tsv'" $< && $(FIX_DATE) && mv $@.tmp $@
figures/soa-acct.pdf: build/scripts/soa-acct.gp $(SOA_POINTS) | $(REPORT_TOOLS)
	@mkdir -p figures
	$(GNUPLOT) -e "infile='$(SOA_POINTS)'" $< && $(FIX_DATE) && mv $@.tmp $@
PROFILES := $(foreach r,1 10,build/results/profile-$(r).tsv build/results/profile-$(r)-rotation.tsv)
figures/profile.pdf: build/scripts/profile.gp $(PROFILES) | $(REPORT_TOOLS)
	@mkdir -p figures
	$(GNUPLOT) -e "lowfile='build/results/profile-1.tsv'; highfile='build/results/profile-10.tsv'" \
	  -e "lowrotfile='build/results/profile-1-rotation.tsv'; highrotfile='build/results/profile-10-rotation.tsv'" \
	  $< && $(FIX_DATE) && mv $@.tmp $@

# ---------------------------------------------------------------- tables and figures -> report
build/paper.tex: paper.nw | $(REPORT_TOOLS)
	noweave -delay -index paper.nw | cpif $@

define run_pdflatex
cd build && for pass in 1 2 3; do \
  pdflatex -interaction=nonstopmode -halt-on-error paper.tex >pdflatex.log \
  || { tail -30 pdflatex.log; exit 1; }; done
@! grep -E 'Warning.*undefined|Citation.*undefined' build/pdflatex.log
endef

build/paper.pdf: build/paper.tex $(RESULT_TABLES) $(FIGURES)
	$(run_pdflatex)

.PHONY: report reproduce paper
report: build/paper.pdf
reproduce: build/paper.pdf

# The PDF from the committed results/ and figures/, for readers without the data: nothing is re-run.
paper: build/paper.tex | $(REPORT_TOOLS)
	$(run_pdflatex)

# ---------------------------------------------------------------- benchmark
.PHONY: bench
bench: bin/tortuosity
	@files=$$(ls '$(DATA_DIR)'/brava-3darteryvis/allscans/*/*.swc); \
	for jobs in 1 2; do \
	  start=$$(date +%s.%N); \
	  ./bin/tortuosity metrics -q --jobs $$jobs --rates 1,2,10,100 $$files >build/bench-$$jobs.tsv; \
	  end=$$(date +%s.%N); \
	  echo "bench: BraVa $$(($$(wc -l <build/bench-$$jobs.tsv) - 1)) vessel-rates, $$jobs thread(s):" \
	       "$$(awk -v a=$$start -v b=$$end 'BEGIN { printf "%.2f", b - a }') s"; \
	done; cmp build/bench-1.tsv build/bench-2.tsv && echo "bench: output identical for 1 and 2 threads"

# ---------------------------------------------------------------- clean
.PHONY: clean
clean:
	rm -rf bin build/src build/obj build/scripts build/results build/sanitize build/fuzz build/unit-tests \
	  build/*.log build/paper.* build/*.tsv
