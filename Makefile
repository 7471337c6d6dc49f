# The tortuosity package: a map from paper.nw and the data to results, figures and the report.
#
#   make              tangle paper.nw and build bin/tortuosity
#   make check        unit tests (from paper.nw) and end-to-end checks (tests/)
#   make reproduce    data -> results/ -> figures/ -> build/paper.pdf
#   make report       build/paper.pdf (runs whatever results it needs)
#   make bench        timing of the full BraVa set
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
CFLAGS  ?= -O2
CFLAGS  += -std=c11 -D_GNU_SOURCE -Wall -Wextra -fopenmp
LDLIBS  := -lgsl -lgslcblas -lm

# ---------------------------------------------------------------- tools
# Debian packages that provide what each stage needs; installed on demand.
BUILD_PACKAGES  := make gcc libc6-dev noweb libgsl-dev
REPORT_PACKAGES := gnuplot-nox r-base-core texlive-latex-base texlive-latex-recommended \
                   texlive-fonts-recommended lmodern
BUILD_TOOLS  := build/.tools-build
REPORT_TOOLS := build/.tools-report

define ensure_packages
if ! $(2); then \
  if [ "$$(id -u)" = 0 ]; then \
    echo "installing: $(1)"; \
    apt-get update -qq; \
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $(1) >/dev/null; \
  else \
    echo "Some tools are missing. Install them with:"; \
    echo "  sudo apt-get install $(1)"; \
    exit 1; \
  fi; \
fi
endef

$(BUILD_TOOLS):
	@mkdir -p build
	@$(call ensure_packages,$(BUILD_PACKAGES),command -v notangle cpif noroots $(CC) >/dev/null && [ -e /usr/include/gsl/gsl_bspline.h ])
	@touch $@

$(REPORT_TOOLS): | $(BUILD_TOOLS)
	@$(call ensure_packages,$(REPORT_PACKAGES),command -v gnuplot Rscript pdflatex noweave >/dev/null && kpsewhich booktabs.sty >/dev/null)
	@touch $@

# ---------------------------------------------------------------- tangle
MODULES := vessel readers pspline stencil metrics frenet phantom pipeline
HEADERS := $(addprefix build/src/,geom.h $(addsuffix .h,$(MODULES)))
LIB_OBJ := $(addprefix build/obj/,$(addsuffix .o,$(MODULES)))
C_ROOTS := $(addprefix src/,geom.h $(addsuffix .h,$(MODULES)) $(addsuffix .c,$(MODULES)) \
             tortuosity.c unit-tests.c)
ROOTS   := $(C_ROOTS)
.SECONDARY: $(addprefix build/,$(C_ROOTS))   # tangled files are kept, so cpif can compare

build/src/%: paper.nw | $(BUILD_TOOLS)
	@mkdir -p $(dir $@)
	notangle -L -R'src/$*' paper.nw | cpif $@

build/obj/%.o: build/src/%.c $(HEADERS)
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

.PHONY: lint
lint: | $(BUILD_TOOLS)
	@diff <(noroots paper.nw | sed 's/^<<\(.*\)>>$$/\1/' | sort) <(printf '%s\n' $(ROOTS) | sort) \
	  && echo "lint: chunk roots match the Makefile" \
	  || { echo "lint: roots of paper.nw ('<') differ from the Makefile ('>'); a misspelled chunk name?"; exit 1; }

# ---------------------------------------------------------------- report
build/paper.tex: paper.nw | $(REPORT_TOOLS)
	noweave -delay -index paper.nw | cpif $@

build/paper.pdf: build/paper.tex
	cd build && for pass in 1 2 3; do \
	  pdflatex -interaction=nonstopmode -halt-on-error paper.tex >pdflatex.log \
	  || { tail -30 pdflatex.log; exit 1; }; done
	@grep -E 'Warning.*undefined|Citation.*undefined' build/pdflatex.log && exit 1 || true

.PHONY: report reproduce
report: build/paper.pdf
reproduce: build/paper.pdf

# ---------------------------------------------------------------- benchmark
.PHONY: bench
bench: bin/tortuosity
	@files=$$(ls '$(DATA_DIR)'/brava-3darteryvis/allscans/*/*.swc); \
	for jobs in 1 2; do \
	  start=$$(date +%s.%N); \
	  ./bin/tortuosity metrics -q --jobs $$jobs --rates 1,2,10,100 $$files >build/bench-$$jobs.tsv; \
	  end=$$(date +%s.%N); \
	  echo "bench: BraVa $$(($$(wc -l <build/bench-$$jobs.tsv) - 1)) vessel-rates, $$jobs thread(s): $$(echo "$$end - $$start" | bc) s"; \
	done; cmp build/bench-1.tsv build/bench-2.tsv && echo "bench: output identical for 1 and 2 threads"

# ---------------------------------------------------------------- clean
.PHONY: clean
clean:
	rm -rf bin build/src build/obj build/unit-tests build/*.log build/paper.* build/*.tsv
