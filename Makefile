# The tortuosity package: a map from paper.nw and the data to results, figures and the report.
#
#   make              tangle paper.nw and build bin/tortuosity
#   make check        unit tests (from paper.nw) and end-to-end checks (tests/)
#   make reproduce    data -> results/ -> figures/ -> build/paper.pdf
#   make report       build/paper.pdf (runs whatever results it needs)
#   make paper        build/paper.pdf from the committed results/ and figures/ (no data needed)
#   make fidelity     the fidelity benchmark: a sweep of curves of known curvature and torsion ->
#                     results/fidelity.tsv, and the summary against its acceptance (and the
#                     torsion under --torsion significant)
#   make bench        timing of the full BraVa set (median of BENCH_RUNS runs, 1 and 2 threads);
#                     BENCH_BASELINE=old/tortuosity: the ratio to an older build, run by run
#   make bench-shards what the first and the last shard of 8 cost against the whole run (text, SWC)
#   make bench-stages where its time goes, stage by stage (perf); RATES=100: at that rate alone
#   make memory       peak memory of metrics on 10^4, 10^5 and 10^6 vessels, and of one
#                     vessel of 10^6 points at 100X
#   make install      program, library, header, pkg-config file and manual page under PREFIX
#                     (default /usr/local; DESTDIR for staging)
#   make check-sanitize   the tests under AddressSanitizer and UndefinedBehaviorSanitizer
#   make fuzz         libFuzzer on each reader (FUZZ_SECONDS per reader, default 150)
#   make lint         chunk roots of paper.nw against the list below
#   make clean
#
# Real data are read from DATA_DIR (never copied); data/manifest.tsv lists them.
# Tools (Debian packages) are installed on first use; the rules are at the end.

SHELL := /bin/bash
.SHELLFLAGS := -o pipefail -ec
.DELETE_ON_ERROR:
.SUFFIXES:
.SECONDEXPANSION:
MAKEFLAGS += --no-builtin-rules

# The tools stages (their Debian packages are listed at the end): TOOLS_build, TOOLS_report, ...
TOOL_STAGES := build report test fuzz bench parallel peers
$(foreach s,$(TOOL_STAGES),$(eval TOOLS_$(s) := build/.tools-$(s)))

DATA_DIR ?= ../shared/data
# Globs and sorts in byte order, whatever the caller's locale: its collation would reorder the
# files of a dataset, so the rows of the results and the listing the data's digest is taken of.
# (LC_ALL would override LC_COLLATE; the character set stays the caller's.)
unexport LC_ALL
export LC_COLLATE := C
START_TIME := $(shell date +%s)
export SOURCE_DATE_EPOCH ?= 1795305600

CC      ?= cc
CFLAGS  ?= -O3
# -fno-math-errno: sqrt and friends never set errno here (nothing reads it), so
# the compiler may use the square-root instruction without a call beside it.
# -fno-trapping-math: nothing reads the floating-point exception flags, so a loop may compute
# both sides of a choice and pick one (the branch-free loops vectorise); values are unchanged.
# HAVE_INLINE: GSL's element accessors inline (its documented switch), range checks kept.
CFLAGS  += -std=c11 -D_GNU_SOURCE -Wall -Wextra -fopenmp -pthread -fno-math-errno -fno-trapping-math -DHAVE_INLINE
# HDF5's paths come from pkg-config once the build tools are installed (hence '=').
HDF5_CFLAGS = $(shell pkg-config --cflags hdf5)
HDF5_LIBS   = $(shell pkg-config --libs hdf5)
LDLIBS   = -lgsl -lgslcblas -lexpat -ljansson -lz -llz4 -llzma -lcrypto $(HDF5_LIBS) -lm

# ---------------------------------------------------------------- the program
.PHONY: all
all: bin/tortuosity setup.py pyproject.toml

SHARED_MODULES := vessel decimal                  # what every part shares: the vessel, numbers as text
MODULES := twin phantom rate pipeline result samples torsion-stretches measure-se sufficient band eigen gcv scatter hermite pspline pspline-eval pspline-check pspline-se stencil metrics frenet study   # the method, in the order of paper.nw
# The readers in layers (each calls only those before it): bytes as text, the shared layer, the
# formats (one file each, src/format-NAME.c, found in paper.nw; their rows are in formats.h, and
# VTK's two share vtk-data), the table and dispatch.
READER_MODULES := bytes reader vtk-data readers
FORMAT_MODULES := $(shell sed -n 's|^<<src/\(format-[a-z0-9-]*\)\.c>>=$$|\1|p' paper.nw)
API_MODULES    := tortuosity                      # the library's public interface, tortuosity.h
# The command line by job (each calls only those before it): text buffers, atomic output and
# provenance, the table and VTK writers, the stream of windows and shards, the commands.
CLI_MODULES    := textbuf suggest output writers stream options cli
PLAIN_HEADERS  := geom.h formats.h pspline-types.h tortuosity.h   # headers of types alone, without a .c
LIB_MODULES := $(SHARED_MODULES) $(MODULES) $(READER_MODULES) $(FORMAT_MODULES) $(API_MODULES)   # the library
HEADERS := $(addprefix build/src/,$(PLAIN_HEADERS) $(addsuffix .h,$(SHARED_MODULES) $(MODULES) $(READER_MODULES) $(CLI_MODULES)))
LIB_OBJ := $(addprefix build/obj/,$(addsuffix .o,$(LIB_MODULES)))
CLI_OBJ := $(addprefix build/obj/,$(addsuffix .o,$(CLI_MODULES)))
C_ROOTS := $(addprefix src/,$(PLAIN_HEADERS) $(addsuffix .h,$(SHARED_MODULES) $(MODULES) $(READER_MODULES) $(CLI_MODULES)) \
             $(addsuffix .c,$(LIB_MODULES) $(CLI_MODULES)) \
             unit-tests.c fuzz-readers.c fidelity-sweep.c)
SCRIPTS := scripts/analysis.R scripts/phantom-tables.R scripts/recon-error.gp scripts/percent-shift.gp scripts/soa-acct.gp \
           scripts/profile.gp scripts/territories.gp scripts/data-views.gp scripts/frame.gp \
           scripts/profile-filtered.gp scripts/aorta-profile.gp scripts/interfaces.awk scripts/slurm-shards.sh \
           scripts/man-commands.awk scripts/bench-stages.awk scripts/tools-lint.sh scripts/shell-commands.awk \
           scripts/structure.sh scripts/modules.awk scripts/concordance-tsv.awk scripts/concordance-table.awk \
           scripts/metrics-table.awk scripts/phantom-truth.awk scripts/fidelity.awk scripts/peers.R scripts/peers.awk \
           scripts/peer-table.awk scripts/median.awk scripts/segments.awk scripts/bench.sh scripts/bench-shards.sh \
           scripts/memory.sh scripts/peer-torsion.awk scripts/quantile.awk scripts/fidelity-declared.sh \
           scripts/fidelity-declared.awk
ROOTS   := $(C_ROOTS) $(SCRIPTS) concordance tortuosity.pc.in man/tortuosity.1 man/tortuosity.1.end \
           python/tortuosity.py setup.py pyproject.toml
.SECONDARY: $(addprefix build/,$(ROOTS))   # tangled files are kept, so cpif can compare

# Tangling: one pass writes every file the build reads from paper.nw (the C sources, with #line
# marks that point into it; the scripts; the installed header, without them; the Python module;
# the two files pip reads at the top). cpif replaces a file only where its text changed, so only
# what is built from a changed file is built again. The pass runs when paper.nw changes or a file
# is missing, and build/tangled records it: the files cpif leaves alone keep their older times,
# and a rule per file would tangle each of them again on every run of make.
TANGLED := $(addprefix build/,$(C_ROOTS) $(SCRIPTS)) build/include/tortuosity.h build/python/tortuosity.py \
           setup.py pyproject.toml
tangle = notangle $(1) -R"$(2)" paper.nw | cpif "$(3)"
build/tangled: paper.nw $(if $(filter-out $(wildcard $(TANGLED)),$(TANGLED)),FORCE) | $(TOOLS_build)
	@echo "notangle paper.nw -> $(words $(TANGLED)) files (those whose text changed)"
	@mkdir -p $(sort $(dir $(TANGLED)))
	@set -e -o pipefail; \
	for root in $(C_ROOTS); do $(call tangle,-L,$$root,build/$$root); done; \
	for root in $(SCRIPTS); do $(call tangle,,$$root,build/$$root); done; \
	$(call tangle,,src/tortuosity.h,build/include/tortuosity.h); \
	$(call tangle,,python/tortuosity.py,build/python/tortuosity.py); \
	for root in setup.py pyproject.toml; do $(call tangle,,$$root,$$root); done
	@touch $@
$(TANGLED): build/tangled ;

# Objects also depend on the Makefile, so a change of flags rebuilds them.
build/obj/%.o: build/src/%.c $(HEADERS) Makefile | $(TOOLS_build)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Ibuild/src $(HDF5_CFLAGS) -c -o $@ $<

# The version, declared here once, and the commit the program is built from, for --version and
# the provenance of every result ("+modified" when paper.nw or the Makefile differ from it).
VERSION := 1.2.0
build/src/version.h: FORCE | $(TOOLS_build)
	@mkdir -p $(@D)
	@commit=$$(git -C '$(CURDIR)' rev-parse --short=12 HEAD 2>/dev/null) || commit=unknown; \
	if [ $$commit != unknown ] && ! git -C '$(CURDIR)' diff --quiet HEAD -- paper.nw Makefile; then \
	  commit=$$commit+modified; fi; \
	printf '#define TORT_VERSION "%s"\n#define TORT_COMMIT "%s"\n' '$(VERSION)' "$$commit" | cpif $@
$(foreach d,obj sanitize pic,$(foreach m,cli output tortuosity,build/$(d)/$(m).o)): build/src/version.h

bin/tortuosity: $(CLI_OBJ) $(LIB_OBJ) | $(TOOLS_build)
	@mkdir -p bin
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

build/unit-tests: build/obj/unit-tests.o $(LIB_OBJ) build/obj/textbuf.o | $(TOOLS_build)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)
# A unit test registers itself by its definition: the program runs every 'static void test_NAME(void)'
# of its source, in order.
build/src/unit-test-list.h: build/src/unit-tests.c | $(TOOLS_build)
	sed -n 's/^static void \(test_[a-z0-9_]*\)(void)$$/RUN(\1);/p' $< | cpif $@
build/obj/unit-tests.o build/sanitize/unit-tests.o: build/src/unit-test-list.h

# ---------------------------------------------------------------- library, manual page, installation
# libtortuosity.a: the modules as one object in which only the tort_ names of tortuosity.h stay global.
build/lib/libtortuosity.a: $(LIB_OBJ) | $(TOOLS_build)
	@mkdir -p $(@D)
	ld -r -o build/lib/tortuosity.o $^
	nm -g --defined-only build/obj/tortuosity.o | awk '$$3 ~ /^tort_/ { print $$3 }' >build/lib/public.syms
	objcopy --keep-global-symbols=build/lib/public.syms build/lib/tortuosity.o
	rm -f $@ && ar rcs $@ build/lib/tortuosity.o

# libtortuosity.so: the same modules as position-independent code; a version script keeps only
# the tort_ names global. Its soname changes when tortuosity.h changes incompatibly.
SOVERSION := 1
SHARED_LIB := build/lib/libtortuosity.so.$(VERSION)
PIC_OBJ := $(addprefix build/pic/,$(addsuffix .o,$(LIB_MODULES)))
build/pic/%.o: build/src/%.c $(HEADERS) Makefile | $(TOOLS_build)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -fPIC -Ibuild/src $(HDF5_CFLAGS) -c -o $@ $<
$(SHARED_LIB): $(PIC_OBJ) | $(TOOLS_build)
	@mkdir -p $(@D)
	printf 'TORTUOSITY_%s {\n  global: tort_*;\n  local: *;\n};\n' $(SOVERSION) >build/lib/tortuosity.map
	$(CC) $(CFLAGS) -shared -Wl,-soname,libtortuosity.so.$(SOVERSION) -Wl,--version-script=build/lib/tortuosity.map \
	  -o $@ $^ $(LDLIBS)
	ln -sf $(@F) build/lib/libtortuosity.so.$(SOVERSION) && ln -sf $(@F) build/lib/libtortuosity.so

# pip install . (setup.py): the module and the shared library side by side in a package folder.
# setup.py and pyproject.toml are tangled to the top of the tree, where pip looks, and committed.
.PHONY: pip-package
pip-package: build/pip/tortuosity/__init__.py build/pip/tortuosity/libtortuosity.so.1
build/pip/tortuosity/__init__.py: build/python/tortuosity.py
	@mkdir -p $(@D)
	cp $< $@
build/pip/tortuosity/libtortuosity.so.1: $(SHARED_LIB)
	@mkdir -p $(@D)
	cp $< $@

PREFIX  ?= /usr/local
DESTDIR ?=
PYTHON_DIR = lib/python3/dist-packages
# Remade on every run (PREFIX is in it), replaced only when it changes.
build/tortuosity.pc: paper.nw FORCE | $(TOOLS_build)
	@notangle -R'tortuosity.pc.in' paper.nw | sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' \
	  -e 's|@LIBS@|$(filter-out -lm,$(LDLIBS)) -fopenmp -lm|' | cpif $@

# The page: its sections from paper.nw, then each command's --help.
MAN_DATE = $(shell date -u -d @$(SOURCE_DATE_EPOCH) +%Y-%m-%d)
build/tortuosity.1: paper.nw bin/tortuosity build/scripts/man-commands.awk | $(TOOLS_build)
	{ notangle -R'man/tortuosity.1' paper.nw | sed -e 's|@DATE@|$(MAN_DATE)|' -e 's|@VERSION@|$(VERSION)|'; \
	  { echo "== main"; ./bin/tortuosity --help; \
	    for c in metrics profile sufficient phantom phantom-study; do echo "== $$c"; ./bin/tortuosity $$c --help; done; \
	    echo "== metric-list"; ./bin/tortuosity metrics --list-metrics; \
	    echo "== format-list"; ./bin/tortuosity --list-formats; } \
	  | awk -f build/scripts/man-commands.awk; notangle -R'man/tortuosity.1.end' paper.nw; } >$@.tmp && mv $@.tmp $@

.PHONY: install uninstall
INSTALLED := bin/tortuosity lib/libtortuosity.a lib/libtortuosity.so.$(VERSION) lib/libtortuosity.so.$(SOVERSION) \
             lib/libtortuosity.so include/tortuosity.h lib/pkgconfig/tortuosity.pc share/man/man1/tortuosity.1 \
             $(PYTHON_DIR)/tortuosity.py
INSTALL_INPUTS := bin/tortuosity build/lib/libtortuosity.a $(SHARED_LIB) build/include/tortuosity.h build/tortuosity.pc \
                  build/tortuosity.1 build/python/tortuosity.py
install: $(INSTALL_INPUTS)
	install -d '$(DESTDIR)$(PREFIX)'/{bin,lib/pkgconfig,include,share/man/man1,$(PYTHON_DIR)}
	install -m 755 bin/tortuosity '$(DESTDIR)$(PREFIX)/bin/'
	install -m 644 build/lib/libtortuosity.a $(SHARED_LIB) '$(DESTDIR)$(PREFIX)/lib/'
	ln -sf libtortuosity.so.$(VERSION) '$(DESTDIR)$(PREFIX)/lib/libtortuosity.so.$(SOVERSION)'
	ln -sf libtortuosity.so.$(VERSION) '$(DESTDIR)$(PREFIX)/lib/libtortuosity.so'
	install -m 644 build/include/tortuosity.h '$(DESTDIR)$(PREFIX)/include/'
	install -m 644 build/tortuosity.pc '$(DESTDIR)$(PREFIX)/lib/pkgconfig/'
	install -m 644 build/tortuosity.1 '$(DESTDIR)$(PREFIX)/share/man/man1/'
	install -m 644 build/python/tortuosity.py '$(DESTDIR)$(PREFIX)/$(PYTHON_DIR)/'
	@if [ -f build/paper.pdf ]; then install -d '$(DESTDIR)$(PREFIX)/share/doc/tortuosity' && \
	  install -m 644 build/paper.pdf '$(DESTDIR)$(PREFIX)/share/doc/tortuosity/' && \
	  echo "install: the report in $(PREFIX)/share/doc/tortuosity/paper.pdf"; \
	else echo "install: no report installed: build/paper.pdf is not built ('make reproduce' makes it)"; fi
uninstall:
	rm -f $(addprefix '$(DESTDIR)$(PREFIX)'/,$(INSTALLED) share/doc/tortuosity/paper.pdf)

# ---------------------------------------------------------------- the experiment grid
# Declared once; passed to the program, to R and to gnuplot.
DATASETS       := $(shell awk -F'\t' 'NR > 1 { print $$1 }' data/manifest.tsv)
RADII_DATASETS := $(shell awk -F'\t' 'NR > 1 && $$5 != "none" { print $$1 }' data/manifest.tsv)
RATES          := 1 2 10 100
INTEGRATORS    := backward-euler rotation bishop
# filtered: Bullitt's filter, backward Euler. Names in words, for tables and figures (~ is a space).
VARIANTS       := $(INTEGRATORS) filtered
VARIANT_NAMES  := backward~Euler rotation Bishop filtered~(backward~Euler)
SHAPES         := circle helix salkowski
NOISES         := clean noisy
PROFILE_RATES  := 1 10
# The twelve metrics of the paper's Figure 6.
SHIFT_METRICS  := AC AT ACCT TC TT TCCT TC_L TT_L TCCT_L SOA IC_kappa IC_N
comma := ,
space := $(subst ,, )
RATE_LIST := $(subst $(space),$(comma),$(RATES))

# What each variant adds to the command line.
OPTIONS_backward-euler :=
OPTIONS_rotation       := --integrator rotation
OPTIONS_bishop         := --integrator bishop
OPTIONS_filtered       := --filter

# ---------------------------------------------------------------- data -> results
# Per-vessel results (large, not committed), each written atomically by tortuosity -o.

# The dataset's files under DATA_DIR, from the manifest (a shell array), or a stop.
manifest_field = awk -F'\t' -v d='$(1)' '$$1 == d { print $$$(2) }' data/manifest.tsv
manifest_value = $(shell $(call manifest_field,$(1),$(2)))
define dataset_files
pattern=$$($(call manifest_field,$(1),2)); \
shopt -s nullglob; files=('$(DATA_DIR)'/$$pattern); \
if [ $${#files[@]} -eq 0 ]; then \
  echo "$(DATA_DIR)/$$pattern: no such files; give the data directory as DATA_DIR=..." >&2; exit 2; fi
endef
# How a dataset is read: its unit, where the manifest gives one, and its reading options.
read_options = $(shell awk -F'\t' -v d='$(1)' '$$1 == d { if ($$4 ~ /^(mm|um|m)$$/) printf "--units %s ", $$4; \
                 if ($$8 != "-") printf "%s", $$8 }' data/manifest.tsv)

# Each dataset's files checked against the manifest before any result is made from them: the
# sha256 of their sha256sum listing (paths relative to DATA_DIR). Checked on every run; the
# stamp changes only with the digest, so results are remade only when the data change.
.PHONY: FORCE
build/data/%.sha256: data/manifest.tsv FORCE
	@mkdir -p $(@D)
	@$(call dataset_files,$*); expected=$$($(call manifest_field,$*,9)); \
	found=$$(cd '$(DATA_DIR)' && files=($$pattern) && sha256sum -- "$${files[@]}" | sha256sum | cut -c1-64); \
	if [ "$$found" != "$$expected" ]; then \
	  echo "$(DATA_DIR)/$$pattern: these are not the files the results were made from:" \
	       "sha256 of their listing $$found, data/manifest.tsv says $$expected" >&2; \
	  echo "  (list them with: cd $(DATA_DIR) && sha256sum $$pattern)" >&2; exit 2; fi; \
	echo "$$found" | cmp -s - $@ || echo "$$found" >$@

# Every measurement of a dataset is one recipe: $(call measure,DATASET,MESSAGE,WORDS[,INDEX[,OUTPUT]])
# runs ./bin/tortuosity WORDS with the dataset's reading options, -o OUTPUT (default $@), on all its
# files (or on "${files[INDEX]}" alone); MESSAGE, if any, is echoed first.
define measure
@mkdir -p $(dir $(or $(5),$@))
@$(call dataset_files,$(1)); $(if $(2),echo "$(2)"; )\
./bin/tortuosity $(3) $(call read_options,$(1)) -o $(or $(5),$@) "$${files[$(or $(4),@)]}"
endef
# What a measurement needs; the dataset is the target's file name ($$(*F), at secondary expansion).
MEASURED = data/manifest.tsv bin/tortuosity build/data/$$(*F).sha256
# $(call cell,TARGET,NAME=VALUE ...) is TARGET, each NAME set to VALUE in its recipe (private: not in
# its prerequisites'), so that a grid's coordinates are variables, not words of the path.
cell = $(foreach v,$(2),$(eval $(1): private $(subst =, := ,$(v))))$(1)

# Every dataset at every rate, measured each way (VARIANTS) and under the significant torsion
# reading, in one run that fits each vessel once (metrics --variant):
# build/results/VARIANT/DATASET.tsv, and build/results/noise/significant/data/DATASET.tsv.
RUNS := $(foreach v,$(VARIANTS),$(foreach d,$(DATASETS),build/results/$(v)/$(d).tsv))
# The first variant is the run's own reading (backward Euler, no options); the others are its --variant.
every_way = $(foreach v,$(wordlist 2,9,$(VARIANTS)),--variant '$(OPTIONS_$(v)) -o build/results/$(v)/$(1).tsv') \
            --variant '--torsion significant -o build/results/noise/significant/data/$(1).tsv'
$(foreach v,$(VARIANTS),build/results/$(v)/%.tsv) build/results/noise/significant/data/%.tsv: $(MEASURED)
	@mkdir -p $(foreach v,$(VARIANTS),build/results/$(v)) build/results/noise/significant/data
	$(call measure,$*,measure $*: $${#files[@]} file(s)$(comma) every way,metrics -q --rates $(RATE_LIST) \
	  $(call every_way,$*),,build/results/$(firstword $(VARIANTS))/$*.tsv)

# Torsion or noise: every dataset and its null twins (straight, planar; on the dataset's own
# precision, the manifest's last column), under the paper's torsion reading and under the
# significant one: build/results/noise/READING/TWIN/DATASET.tsv, TWIN = data, straight or planar.
# The data's own readings are the runs above (the paper's: the backward-Euler run, which R reads);
# each twin is measured under both readings in one run.
NOISE_READINGS := paper significant
NOISE_TWINS    := data straight planar
NOISE_RUNS     := $(filter-out build/results/noise/paper/data/%,\
                    $(foreach r,$(NOISE_READINGS),$(foreach t,$(NOISE_TWINS),$(foreach d,$(DATASETS),\
                    build/results/noise/$(r)/$(t)/$(d).tsv))))
define null_twin_runs   # the rule of TWIN $(1)'s runs
build/results/noise/paper/$(1)/%.tsv build/results/noise/significant/$(1)/%.tsv: $$(MEASURED)
	@mkdir -p build/results/noise/significant/$(1)
	$$(call measure,$$*,noise: $$*$$(comma) $(1) twin,metrics -q --rates $$(RATE_LIST) --null $(1) \
	  --precision '$$(call manifest_value,$$*,10)' \
	  --variant '--torsion significant -o build/results/noise/significant/$(1)/$$*.tsv',,build/results/noise/paper/$(1)/$$*.tsv)
endef
$(foreach t,$(filter-out data,$(NOISE_TWINS)),$(eval $(call null_twin_runs,$(t))))

# The smallest sufficient rate per vessel, for the datasets with radii, with each integrator in one
# run: build/results/sufficient/INTEGRATOR/DATASET.tsv.
SUFFICIENT := $(foreach i,$(INTEGRATORS),$(foreach d,$(RADII_DATASETS),build/results/sufficient/$(i)/$(d).tsv))
each_integrator = $(foreach i,$(wordlist 2,9,$(INTEGRATORS)),--variant '--integrator $(i) -o build/results/sufficient/$(i)/$(1).tsv')
$(foreach i,$(INTEGRATORS),build/results/sufficient/$(i)/%.tsv): $(MEASURED)
	@mkdir -p $(foreach i,$(INTEGRATORS),build/results/sufficient/$(i))
	$(call measure,$*,sufficient rate: $*,sufficient -q --integrator $(firstword $(INTEGRATORS)) $(call each_integrator,$*),,\
	  build/results/sufficient/$(firstword $(INTEGRATORS))/$*.tsv)

# Views of the data (the paper's Figure 1): every vessel of the first file of each dataset, raw,
# and a Salkowski phantom: build/results/views/NAME.tsv.
VIEWS := $(foreach d,$(DATASETS),build/results/views/$(d).tsv)
$(VIEWS): build/results/views/%.tsv: $(MEASURED)
	$(call measure,$*,,profile -q --rate raw --vessel all,0)
build/results/views/salkowski.tsv: bin/tortuosity
	@mkdir -p $(@D)
	./bin/tortuosity phantom --shape salkowski | ./bin/tortuosity profile -q --rate raw -o $@ -

# The Frenet-Serret frame on one period of a sinusoid (the paper's Figure 2).
build/results/sinusoid.tsv: bin/tortuosity
	@mkdir -p $(@D)
	awk 'BEGIN { for (i = 0; i <= 24; i++) { x = 8 * atan2(0, -1) * i / 24; print x, 2 * sin(x / 4), 0 } }' \
	  | ./bin/tortuosity profile -q --rate 2 -o $@ -

# The paper's own densities for its data, in points per mm (Bullitt's 2, O'Flynn's 5,
# Vorobtsova's 10), applied to the datasets that stand in for them: build/results/density/DATASET.tsv.
PAPER_DENSITIES := brava-3darteryvis:2 aorta-ct:5 coronary-ct:10
DENSITY_RUNS    := $(foreach p,$(PAPER_DENSITIES),build/results/density/$(firstword $(subst :, ,$(p))).tsv)
density_of       = $(lastword $(subst :, ,$(filter $(1):%,$(PAPER_DENSITIES))))

# O'Flynn's curvature and torsion along the arteries at 5 points/mm (its Figure S3), on the aorta.
build/results/density/aorta-ct-profile.tsv: data/manifest.tsv bin/tortuosity build/data/aorta-ct.sha256
	$(call measure,aorta-ct,,profile -q --rate $(call density_of,aorta-ct)/mm --vessel all,0)

$(DENSITY_RUNS): build/results/density/%.tsv: $(MEASURED)
	$(call measure,$*,measure $* at $(call density_of,$*) points/mm,metrics -q --rates $(call density_of,$*)/mm)

# The phantom study (report, "The phantom study"): each shape at the paper's three noise
# parameters, read as a standard deviation and as a variance, at the two densities the paper
# states, STUDY_COUNT realisations each, plus one noise-free phantom per shape and density:
# build/results/study/FIT/SHAPE/DENSITY/{clean,READING-SIGMA}.tsv, FIT = package or paper.
SIGMAS       := 0.0005 0.001 0.1
READINGS     := sd variance
DENSITIES    := supplement caption
STUDY_COUNT  := 1000
# The one sigma the paper gives each shape.
PAPER_SIGMAS := circle:0.0005 helix:0.1 salkowski:0.001
# The paper's stated fit: quintic (C4), no more than 20 basis functions (15 segments); its
# penalty order is not stated, Eilers and Marx's usual second order is taken.
FIT_package :=
FIT_paper   := --degree 5 --penalty-order 2 --segments 15
# $(call study_cell,FIT,SHAPE,DENSITY[,READING,SIGMA]): one cell, its coordinates its variables
# (no READING: the noise-free phantom).
study_cell  = $(call cell,build/results/study/$(1)/$(2)/$(3)/$(if $(4),$(4)-$(5),clean).tsv,\
                STUDY_FIT=$(1) STUDY_SHAPE=$(2) STUDY_DENSITY=$(3) STUDY_READING=$(4) STUDY_SIGMA=$(5))
# $(call study_cells,FIT,SHAPE,SIGMAS): at each density the noise-free cell, then each reading of each sigma.
study_cells = $(foreach d,$(DENSITIES),$(call study_cell,$(1),$(2),$(d)) \
                $(foreach r,$(READINGS),$(foreach g,$(3),$(call study_cell,$(1),$(2),$(d),$(r),$(g)))))
STUDY_PACKAGE := $(foreach s,$(SHAPES),$(call study_cells,package,$(s),$(SIGMAS)))
STUDY_PAPER   := $(foreach p,$(PAPER_SIGMAS),$(call study_cells,paper,$(word 1,$(subst :, ,$(p))),$(word 2,$(subst :, ,$(p)))))
study_noise = $(if $(STUDY_READING),--reading $(STUDY_READING) --sigma $(STUDY_SIGMA) --count $(STUDY_COUNT))
$(STUDY_PACKAGE) $(STUDY_PAPER): bin/tortuosity
	@mkdir -p $(@D)
	./bin/tortuosity phantom-study --shape $(STUDY_SHAPE) --density $(STUDY_DENSITY) \
	  $(study_noise) --rates $(RATE_LIST) $(FIT_$(STUDY_FIT)) -o $@
# One table per fit, header once, cells in the order of the grid (committed).
results/phantom-summary.tsv: $(STUDY_PACKAGE)
results/phantom-summary-paper-fit.tsv: $(STUDY_PAPER)
results/phantom-summary.tsv results/phantom-summary-paper-fit.tsv:
	@mkdir -p results
	awk 'NR == 1 || FNR > 1' $^ >$@.tmp && mv $@.tmp $@

# The analytic trimmed totals of each shape: build/results/truth/SHAPE.tsv.
build/results/truth/%.tsv: bin/tortuosity
	@mkdir -p $(@D)
	./bin/tortuosity phantom --shape $* --truth -o $@
build/results/phantom-truth.tsv: build/scripts/phantom-truth.awk $(foreach s,$(SHAPES),build/results/truth/$(s).tsv)
	awk -f $< $(filter %.tsv,$^) >$@.tmp && mv $@.tmp $@

# One centerline, sample by sample, for the profile figure: profile-RATE[-rotation].tsv. It is
# vessel 1 of the file the manifest's profile column names, in its dataset's folder (the coronary
# FUMPE file: the pattern also matches the orCaScore file, which sorts first).
PROFILE_DATASET := $(shell awk -F'\t' 'NR > 1 && $$11 != "-" { print $$1; exit }' data/manifest.tsv)
PROFILE_INPUT    = $(DATA_DIR)/$(dir $(call manifest_value,$(PROFILE_DATASET),2))$(call manifest_value,$(PROFILE_DATASET),11)
PROFILE_OPTIONS = --vessel 1 $(call read_options,$(PROFILE_DATASET))
PROFILE_NEEDS   = data/manifest.tsv bin/tortuosity build/data/$(PROFILE_DATASET).sha256
# The same centerline with Bullitt's filter (the paper's Figure 5).
build/results/profile-%-filtered.tsv: $(PROFILE_NEEDS)
	@mkdir -p $(@D)
	./bin/tortuosity profile -q --rate $* $(PROFILE_OPTIONS) --filter -o $@ '$(PROFILE_INPUT)'
build/results/profile-%-rotation.tsv: $(PROFILE_NEEDS)
	@mkdir -p $(@D)
	./bin/tortuosity profile -q --rate $* $(PROFILE_OPTIONS) --integrator rotation -o $@ '$(PROFILE_INPUT)'
build/results/profile-%.tsv: $(PROFILE_NEEDS)
	@mkdir -p $(@D)
	./bin/tortuosity profile -q --rate $* $(PROFILE_OPTIONS) -o $@ '$(PROFILE_INPUT)'

# ---------------------------------------------------------------- results -> tables
# Small summaries, committed. Two R scripts, each writing into a scratch folder of its own, whose
# files are moved into place: the data's tables (analysis.R) and the phantom study's
# (phantom-tables.R). The data's need no phantom, so that make -j2 makes them beside the phantom
# study (see reproduce); only the short phantom script waits for the study.
DATA_TABLES    := results/fit-table.tex results/noise-table.tex results/recon-table.tex \
                  results/recon-length-table.tex results/soa-acct-table.tex results/correlation.tex \
                  results/sufficient-table.tex results/data-tables.tex
DATA_TSVS      := results/recon-error.tsv results/recon-length.tsv results/percent-shift.tsv \
                  results/percent-shift-null.tsv results/fits.tsv results/noise.tsv results/soa-acct.tsv \
                  results/correlation.tsv results/correlation-influence.tsv results/sufficient.tsv \
                  results/territories.tsv results/oflynn-table.tsv results/vorobtsova-table.tsv
PHANTOM_TABLES := results/phantom-table.tex results/phantom-paper-tables.tex
PHANTOM_TSVS   := results/phantom-table1.tsv results/phantom-table2.tsv results/phantom-tableS1.tsv \
                  results/phantom-sensitivity.tsv results/phantom-reading.tsv
RESULT_TABLES  := $(DATA_TABLES) $(PHANTOM_TABLES) results/fidelity-table.tex results/numbers.tex results/peer-table.tex
RESULT_TSVS    := $(DATA_TSVS) $(PHANTOM_TSVS)
SOA_POINTS     := build/results/soa-acct-points.tsv
SUMMARY_TMP    := build/results/summary.tmp
PHANTOM_TMP    := build/results/phantom-tables.tmp
# What both scripts are told: the grid.
R_GRID = rates='$(RATES)' variants='$(VARIANTS)' variant_names='$(VARIANT_NAMES)' integrators='$(INTEGRATORS)' \
         shapes='$(SHAPES)'

# The measurements of the data that the data's tables summarise.
DATA_MEASUREMENTS := $(RUNS) $(NOISE_RUNS) $(SUFFICIENT) $(DENSITY_RUNS) \
                     $(foreach r,$(PROFILE_RATES),build/results/profile-$(r).tsv build/results/profile-$(r)-rotation.tsv)

$(DATA_TABLES) $(DATA_TSVS) $(SOA_POINTS) build/results/numbers-data.tex &: build/scripts/analysis.R \
    $(DATA_MEASUREMENTS) | $(TOOLS_report)
	@rm -rf $(SUMMARY_TMP) && mkdir -p $(SUMMARY_TMP) results
	Rscript --vanilla build/scripts/analysis.R in=build/results out=$(SUMMARY_TMP) points=$(SOA_POINTS).tmp $(R_GRID) \
	  radii='$(RADII_DATASETS)' shift_metrics='$(SHIFT_METRICS)' paper_densities='$(PAPER_DENSITIES)' \
	  profile_rates='$(PROFILE_RATES)' noise_readings='$(NOISE_READINGS)' noise_twins='$(NOISE_TWINS)'
	@mv $(SOA_POINTS).tmp $(SOA_POINTS)
	@mv $(addprefix $(SUMMARY_TMP)/,$(notdir $(DATA_TABLES) $(DATA_TSVS))) results/
	@mv $(SUMMARY_TMP)/numbers.tex build/results/numbers-data.tex

$(PHANTOM_TABLES) $(PHANTOM_TSVS) build/results/numbers-phantoms.tex &: build/scripts/phantom-tables.R \
    results/phantom-summary.tsv results/phantom-summary-paper-fit.tsv build/results/phantom-truth.tsv | $(TOOLS_report)
	@rm -rf $(PHANTOM_TMP) && mkdir -p $(PHANTOM_TMP) results
	Rscript --vanilla build/scripts/phantom-tables.R in=build/results out=$(PHANTOM_TMP) $(R_GRID) \
	  densities='$(DENSITIES)' readings='$(READINGS)' paper_sigmas='$(PAPER_SIGMAS)'
	@mv $(addprefix $(PHANTOM_TMP)/,$(notdir $(PHANTOM_TABLES) $(PHANTOM_TSVS))) results/
	@mv $(PHANTOM_TMP)/numbers.tex build/results/numbers-phantoms.tex

# The fidelity benchmark (report, "How often is a number right"): a sweep of curves whose curvature and
# torsion are known exactly, from one seed, measured at the four rates with the uncertainties, and
# compared with their truth: results/fidelity.tsv, and the report's table and numbers.
FIDELITY_SEED := 1
build/fidelity-sweep: build/src/fidelity-sweep.c | $(TOOLS_build)
	$(CC) $(CFLAGS) -o $@ $< -lgsl -lgslcblas -lm
build/fidelity/curves.txt build/fidelity/truth.tsv &: build/fidelity-sweep
	@mkdir -p $(@D)
	./build/fidelity-sweep --seed $(FIDELITY_SEED) --curves build/fidelity/curves.txt --truth build/fidelity/truth.tsv
build/fidelity/measured.tsv: build/fidelity/curves.txt bin/tortuosity
	./bin/tortuosity metrics -q --uncertainty --rates $(RATE_LIST) -o $@ $<
results/fidelity.tsv: build/scripts/fidelity.awk build/fidelity/truth.tsv build/fidelity/measured.tsv
	awk -f $^ >$@.tmp && mv $@.tmp $@
build/results/numbers-fidelity.tex: build/scripts/fidelity.awk build/fidelity/truth.tsv build/fidelity/measured.tsv
	@mkdir -p $(@D)
	awk -v report=1 -f $^ >$@.tmp && mv $@.tmp $@
results/fidelity-table.tex: build/results/numbers-fidelity.tex
	grep -v '^\\newcommand' $< >$@.tmp && mv $@.tmp $@
# The significant reading of torsion on the same sweep (10X): torsion kept where it is real, and the
# planar curves' torsion zeroed (make fidelity's last lines; not part of reproduce).
build/fidelity/significant.tsv: build/fidelity/curves.txt bin/tortuosity
	./bin/tortuosity metrics -q --uncertainty --torsion significant --rates 10 -o $@ $<
.PHONY: fidelity
fidelity: results/fidelity.tsv results/fidelity-table.tex build/fidelity/significant.tsv
	@awk -v summary=1 -f build/scripts/fidelity.awk build/fidelity/truth.tsv build/fidelity/measured.tsv
	@echo "under --torsion significant (10X):"
	@awk -v summary=1 -f build/scripts/fidelity.awk build/fidelity/truth.tsv build/fidelity/significant.tsv \
	  | awk '/^planar/ { print } /^\(c\)/ { print; getline; print }'

# The sweep's rows snapped to a lattice, at 10X, as they are and with their lattice given (report,
# "Voxel paths"): make fidelity-declared [FIDELITY_DECLARED_SEEDS="2 3 4"]; not part of reproduce.
FIDELITY_DECLARED_SEEDS ?= $(FIDELITY_SEED)
.PHONY: fidelity-declared
fidelity-declared: build/scripts/fidelity-declared.sh build/scripts/fidelity-declared.awk build/fidelity-sweep \
                   bin/tortuosity | $(TOOLS_build)
	bash build/scripts/fidelity-declared.sh ./bin/tortuosity ./build/fidelity-sweep build/fidelity-declared \
	  $(FIDELITY_DECLARED_SEEDS)

# The authors' R code beside the package (report, "The authors' code beside this package"): its own
# calls on the Angicart sample (1, 2, 10 points/um) and the three phantoms (1, 2, 10 points/mm), the
# package at the same densities, and their comparison. Not part of reproduce: results/peer-*.tsv and
# the report's table are committed, and remade by 'make peers'.
PEER_DIR      ?= $(DATA_DIR)/../peers/tortuosity_R/code_and_sample_data
PEER_FIT      := --trim 0 --penalty-order 2
build/peers/phantoms.txt: bin/tortuosity
	@mkdir -p $(@D)
	for s in semicircle helix salkowski; do ./bin/tortuosity phantom --shape $$s; echo; done >$@
build/peers/phantoms-peer.tsv: build/scripts/peers.R build/peers/phantoms.txt | $(TOOLS_peers)
	Rscript build/scripts/peers.R '$(PEER_DIR)' build/peers/phantoms.txt 1,2,10 $@ 2>/dev/null
build/peers/phantoms-package.tsv: build/peers/phantoms.txt bin/tortuosity
	./bin/tortuosity metrics -q $(PEER_FIT) --rates 1/mm,2/mm,10/mm -o $@ $<
build/peers/angicart-peer.tsv: build/scripts/peers.R bin/tortuosity build/data/mouse-angicart.sha256 | $(TOOLS_peers)
	@mkdir -p $(@D)
	@$(call dataset_files,mouse-angicart); Rscript build/scripts/peers.R '$(PEER_DIR)' "$${files[0]}" 1,2,10 $@ 2>/dev/null
build/peers/angicart-package.tsv: bin/tortuosity build/data/mouse-angicart.sha256
	@mkdir -p $(@D)
	@$(call dataset_files,mouse-angicart); ./bin/tortuosity metrics -q $(PEER_FIT) --rates 1000/mm,2000/mm,10000/mm \
	  -o $@ "$${files[0]}"
# peers.awk and peer-torsion.awk (the first prerequisite) take quantile.awk's function.
QUANTILES := awk -f build/scripts/quantile.awk
results/peer-angicart.tsv: build/scripts/peers.awk build/peers/angicart-peer.tsv build/peers/angicart-package.tsv \
                           build/scripts/quantile.awk
	$(QUANTILES) -v scale=0.001 -f $< $(filter %.tsv,$^) >$@.tmp && mv $@.tmp $@
# The peer's frame and metrics alone on the package's own samples (not its fit), per density in points/um.
PEER_DENSITIES := 1 2 10
build/peers/angicart-samples-%.txt: bin/tortuosity build/data/mouse-angicart.sha256
	@mkdir -p $(@D)
	@$(call dataset_files,mouse-angicart); ./bin/tortuosity profile -q $(PEER_FIT) --vessel all --rate $*000/mm \
	  "$${files[0]}" >$@.tmp && mv $@.tmp $@
build/peers/angicart-samples-peer-%.tsv: build/scripts/peers.R build/peers/angicart-samples-%.txt | $(TOOLS_peers)
	Rscript build/scripts/peers.R '$(PEER_DIR)' build/peers/angicart-samples-$*.txt $* $@ samples 1000 2>/dev/null
build/peers/angicart-samples-peer.tsv: $(PEER_DENSITIES:%=build/peers/angicart-samples-peer-%.tsv)
	awk 'FNR > 1 || NR == 1' $^ >$@.tmp && mv $@.tmp $@
results/peer-angicart-samples.tsv: build/scripts/peers.awk build/peers/angicart-samples-peer.tsv \
                                   build/peers/angicart-package.tsv build/scripts/quantile.awk
	$(QUANTILES) -v scale=0.001 -f $< $(filter %.tsv,$^) >$@.tmp && mv $@.tmp $@
results/peer-phantoms.tsv: build/scripts/peers.awk build/peers/phantoms-peer.tsv build/peers/phantoms-package.tsv \
                           build/scripts/quantile.awk
	$(QUANTILES) -v scale=1 -v truth=1 -f $< $(filter %.tsv,$^) >$@.tmp && mv $@.tmp $@
.PHONY: peers
results/peer-tau-max.tsv: build/scripts/peer-torsion.awk build/peers/angicart-samples-peer.tsv build/scripts/quantile.awk
	$(QUANTILES) -f $< $(filter %.tsv,$^) >$@.tmp && mv $@.tmp $@
peers: results/peer-angicart.tsv results/peer-angicart-samples.tsv results/peer-phantoms.tsv \
       results/peer-tau-max.tsv build/scripts/peer-table.awk
	awk -f build/scripts/peer-table.awk results/peer-angicart.tsv results/peer-angicart-samples.tsv \
	  results/peer-phantoms.tsv >results/peer-table.tex.tmp
	mv results/peer-table.tex.tmp results/peer-table.tex

# The report's numbers, the phantoms' first.
results/numbers.tex: build/results/numbers-phantoms.tex build/results/numbers-data.tex build/results/numbers-fidelity.tex
	cat build/results/numbers-phantoms.tex build/results/numbers-data.tex >$@.tmp
	grep '^\\newcommand' build/results/numbers-fidelity.tex >>$@.tmp && mv $@.tmp $@

# The paper's tables and figures with their counterparts (report, near the start), from the
# concordance chunk; 'make reproduce' checks that every file a row names exists.
results/concordance.tsv: paper.nw build/scripts/concordance-tsv.awk | $(TOOLS_build)
	@mkdir -p results
	notangle -R'concordance' $< | awk -f build/scripts/concordance-tsv.awk >$@.tmp && mv $@.tmp $@
check_concordance = awk -F'\t' 'NR > 1 && $$4 != "-" && system("test -f " $$4) { print "$<: " $$1 ": no file " $$4; \
                      bad = 1 } END { exit bad }' $< >&2
build/concordance.tex: build/scripts/concordance-table.awk results/concordance.tsv
	awk -F'\t' -f $^ >$@.tmp && mv $@.tmp $@

# The report's table of metrics and list of interfaces come from the code itself.
build/metrics-table.tex: bin/tortuosity build/scripts/metrics-table.awk
	./bin/tortuosity metrics --list-metrics | awk -F'\t' -f build/scripts/metrics-table.awk >$@.tmp && mv $@.tmp $@
# Section 1's table of modules: the Makefile's lists, layer by layer, each module with the first
# line of its header (or, for a format, of its file), which says its job.
MODULE_LAYERS := shared:geom~$(subst $(space),~,$(SHARED_MODULES)) method:$(subst $(space),~,$(MODULES)) \
                 reading:$(subst $(space),~,$(READER_MODULES) $(FORMAT_MODULES)) \
                 command~line:$(subst $(space),~,$(CLI_MODULES)) library:$(API_MODULES)
build/modules.tex: build/scripts/modules.awk $(HEADERS) $(addprefix build/src/,$(addsuffix .c,$(FORMAT_MODULES))) Makefile
	for layer in $(MODULE_LAYERS); do for m in $$(echo $${layer#*:} | tr '~' ' '); do \
	  f=build/src/$$m.h; [ -f $$f ] || f=build/src/$$m.c; \
	  printf '%s\t%s\t%s\t%s\n' "$$(echo $${layer%%:*} | tr '~' ' ')" $$m $$(basename $$f) "$$(grep -m1 '^/\* .* \*/$$' $$f)"; \
	done; done | awk -F'\t' -f build/scripts/modules.awk >$@.tmp && mv $@.tmp $@
build/interfaces.tex: build/scripts/interfaces.awk $(HEADERS)
	awk -f $< $(filter %.h,$^) >$@.tmp && mv $@.tmp $@

# ---------------------------------------------------------------- tables -> figures
# One rule for every figure: figures/NAME.tex (the text, set by LaTeX) and figures/NAME.pdf (the
# lines) from build/scripts/NAME.gp and its data files FIG_INPUTS_NAME; figures/NAME.png, the
# whole figure as an image, from both.
FIGURE_NAMES := recon-error percent-shift soa-acct profile profile-filtered territories data-views \
                frame aorta-profile
FIGURES      := $(foreach f,$(FIGURE_NAMES),figures/$(f).tex figures/$(f).pdf)
FIGURE_PNGS  := $(foreach f,$(FIGURE_NAMES),figures/$(f).png)
FIG_INPUTS_recon-error      := results/recon-error.tsv
FIG_INPUTS_percent-shift    := results/percent-shift.tsv results/percent-shift-null.tsv
FIG_INPUTS_soa-acct         := $(SOA_POINTS)
FIG_INPUTS_profile          := $(foreach r,$(PROFILE_RATES),build/results/profile-$(r).tsv) \
                               $(foreach r,$(PROFILE_RATES),build/results/profile-$(r)-rotation.tsv)
FIG_INPUTS_profile-filtered := build/results/profile-$(lastword $(PROFILE_RATES)).tsv \
                               build/results/profile-$(lastword $(PROFILE_RATES))-filtered.tsv
FIG_INPUTS_territories      := results/territories.tsv
FIG_INPUTS_data-views       := build/results/views/salkowski.tsv $(VIEWS)
FIG_INPUTS_frame            := build/results/sinusoid.tsv
FIG_INPUTS_aorta-profile    := build/results/density/aorta-ct-profile.tsv
# The figures' inputs are kept: make would otherwise treat those made by a pattern rule as
# intermediate files and delete them at the end of the run.
.SECONDARY: $(foreach f,$(FIGURE_NAMES),$(FIG_INPUTS_$(f)))
DATASET_NAMES := $(shell awk -F'\t' 'NR > 1 { gsub(/ /, "~", $$7); printf "%s ", $$7 }' data/manifest.tsv)

# cairo 1.16 stamps the wall-clock time; replace it (same length) so figures are byte-identical.
PDF_DATE = $(shell date -u -d @$(SOURCE_DATE_EPOCH) +%Y%m%d%H%M%S)
figures/%.tex figures/%.pdf: build/scripts/%.gp $$(FIG_INPUTS_$$*) | $(TOOLS_report)
	@mkdir -p figures build/fig
	gnuplot -e "inputs='$(FIG_INPUTS_$*)'; outfile='build/fig/$*.tex'" \
	  -e "datasets='$(DATASETS)'; dataset_names='$(DATASET_NAMES)'" \
	  -e "variants='$(VARIANTS)'; variant_names='$(VARIANT_NAMES)'" \
	  -e "rates='$(RATES)'; profile_rates='$(PROFILE_RATES)'; shift_metrics='$(SHIFT_METRICS)'" $<
	perl -0777 -pi -e 's{/CreationDate \(D:\d{14}Z\)}{/CreationDate (D:$(PDF_DATE)Z)}' build/fig/$*.pdf
	sed 's#{build/fig/#{../figures/#' build/fig/$*.tex >build/fig/$*.tex.tmp
	mv build/fig/$*.pdf figures/$*.pdf && mv build/fig/$*.tex.tmp figures/$*.tex

# The PNG twin: the figure alone on a page of its own size (its picture is in units of 0.05 bp).
figures/%.png: figures/%.tex figures/%.pdf | $(TOOLS_report)
	@size=$$(sed -n 's/.*\\begin{picture}(\([0-9.]*\),\([0-9.]*\)).*/\1 \2/p' $<); \
	w=$$(echo $$size | awk '{ print $$1 / 20 }'); h=$$(echo $$size | awk '{ print $$2 / 20 }'); \
	cd build && FORCE_SOURCE_DATE=1 pdflatex -interaction=nonstopmode -halt-on-error -jobname=png-$* \
	  "\documentclass{article}\usepackage[paperwidth=$${w}bp,paperheight=$${h}bp,margin=0pt]{geometry}\
	   \usepackage{graphicx,xcolor}\pagestyle{empty}\begin{document}\noindent{\small\input{../$<}}\end{document}" \
	  >png-$*.log || { tail -20 png-$*.log; exit 1; }
	pdftoppm -r 150 -png -singlefile build/png-$*.pdf $(basename $@)

# ---------------------------------------------------------------- tables and figures -> report
build/paper.tex: paper.nw | $(TOOLS_report)
	noweave -delay -index paper.nw | cpif $@

# FORCE_SOURCE_DATE: the date on the page and in the PDF is SOURCE_DATE_EPOCH's, not the build day's.
# A pass is run again while it changed what the next one reads (the cross-references, the contents,
# the bookmarks) or its log asks for it, at most PDFLATEX_PASSES in all: a warm build whose pages
# did not move takes one pass, a cold one four (chunks that break across pages move with the
# page numbers the cross-references print).
PDFLATEX_PASSES := 8
PDFLATEX_READS  := paper.aux paper.toc paper.out
define run_pdflatex
cd build && for pass in $$(seq $(PDFLATEX_PASSES)); do \
  before=$$(cksum $(PDFLATEX_READS) 2>/dev/null || true); \
  FORCE_SOURCE_DATE=1 pdflatex -interaction=nonstopmode -halt-on-error paper.tex >pdflatex.log \
  || { tail -30 pdflatex.log; exit 1; }; \
  [ "$$before" = "$$(cksum $(PDFLATEX_READS) 2>/dev/null || true)" ] && ! grep -q 'Rerun' pdflatex.log && break; \
  [ $$pass -lt $(PDFLATEX_PASSES) ] || { echo "build/paper.pdf: still changing after $$pass passes"; exit 1; }; \
done
@! grep -E 'Warning.*undefined|Citation.*undefined' build/pdflatex.log
@$(check_print)
endef
# Fit for print: no line wider than the text by more than 1 pt, no bitmap (Type 3) font, and a
# book a reader can carry: at most REPORT_MAX_PAGES pages.
REPORT_MAX_PAGES := 356
define check_print
awk '/^Overfull \\hbox/ { w = $$3; sub(/\(/, "", w); if (w + 0 > 1) { print "build/paper.log: " $$0; bad = 1 } } \
  END { exit bad }' build/paper.log \
&& { ! pdffonts build/paper.pdf | grep 'Type 3' || { echo "build/paper.pdf: a Type 3 (bitmap) font"; exit 1; }; } \
&& pages=$$(pdfinfo build/paper.pdf | awk '$$1 == "Pages:" { print $$2 }') \
&& { [ "$$pages" -le $(REPORT_MAX_PAGES) ] || { echo "build/paper.pdf: $$pages pages, more than $(REPORT_MAX_PAGES)"; exit 1; }; }
endef

REPORT_INPUTS := build/paper.tex build/metrics-table.tex build/interfaces.tex build/concordance.tex build/modules.tex

build/paper.pdf: $(REPORT_INPUTS) $(RESULT_TABLES) $(FIGURES) | $(TOOLS_report)
	$(run_pdflatex)

.PHONY: report reproduce paper
report: build/paper.pdf
reproduce: results/concordance.tsv results/fidelity.tsv build/paper.pdf $(FIGURE_PNGS)
	@$(check_concordance)
	@echo "reproduce: the report is build/paper.pdf ($$(($$(date +%s) - $(START_TIME))) s)"
# Under 'make reproduce' the phantom study waits for every measurement of the data. Make starts, in
# one pass over the prerequisites, every target it can as slots free, and the study's 60 cells,
# ready from the start, would take every slot before the data's tables could start; this way R's
# summary of the data (one core, the longest single step) runs beside the study, not after it.
ifneq ($(filter reproduce,$(MAKECMDGOALS)),)
$(STUDY_PACKAGE) $(STUDY_PAPER): | $(DATA_MEASUREMENTS) \
    $(filter-out $(SOA_POINTS),$(filter build/results/%,$(foreach f,$(FIGURE_NAMES),$(FIG_INPUTS_$(f)))))
endif

# The PDF from the committed results/ and figures/, for readers without the data: nothing is re-run.
paper: $(REPORT_INPUTS) | $(TOOLS_report)
	$(run_pdflatex)

# ---------------------------------------------------------------- tests
# Each suite ends with "[name: ]N passed, N failed"; the totals decide.
COUNT_LINE := /^([a-z0-9-]+: )?[0-9]+ passed, [0-9]+ failed$$/
# A locale with a decimal comma, for the test that the library reads numbers alike in any locale
# (built here, since a machine need not have one generated; the definitions come from locales).
TEST_LOCALE := build/locale/de_DE.UTF-8
$(TEST_LOCALE): | $(TOOLS_test)
	@mkdir -p $(dir $@)
	localedef -i de_DE -f UTF-8 $@

# The suites run side by side, JOBS at a time, the longest first; each prints its whole output
# when it ends (--output-sync), and the totals of their logs decide. Every file the suites use is
# built before they start, so the makes they run in this tree (install, lint) only read it. Each
# rule names its tools stamp on its own line, where make lint reads a recipe's stage.
CHECK_SUITES := end-to-end unit-tests reliability python-api pip-install
check_suites  = $(MAKE) -s $(if $(findstring jobserver,$(MAKEFLAGS)),,-j$(JOBS)) --output-sync=target $(1)
check_totals  = awk '$(COUNT_LINE) { p += $$(NF - 3); f += $$(NF - 1) } \
                     END { printf "$(1): %d passed, %d failed\n", p, f; exit f > 0 }' $(2)

CHECK_INPUTS := build/unit-tests bin/tortuosity build/fidelity-sweep build/scripts/fidelity.awk \
                build/scripts/slurm-shards.sh build/scripts/structure.sh $(INSTALL_INPUTS) $(TEST_LOCALE)

.PHONY: check $(addprefix check-,$(CHECK_SUITES))
check $(addprefix check-,$(CHECK_SUITES)): $(CHECK_INPUTS)
check: | $(TOOLS_test)
	@$(call check_suites,$(addprefix check-,$(CHECK_SUITES)))
	@$(call check_totals,check,$(addprefix build/,$(addsuffix .log,$(CHECK_SUITES))))
check-unit-tests: | $(TOOLS_test)
	@echo "== unit tests (paper.nw)"
	@./build/unit-tests | tee build/unit-tests.log
check-end-to-end: | $(TOOLS_test)
	@echo "== end-to-end checks (tests/)"
	@DATA_DIR='$(DATA_DIR)' REPO='$(CURDIR)' bash tests/end-to-end.sh bin/tortuosity | tee build/end-to-end.log
check-reliability: | $(TOOLS_test)
	@echo "== reliability checks (tests/)"
	@bash tests/reliability.sh bin/tortuosity | tee build/reliability.log
check-python-api: | $(TOOLS_test)
	@echo "== the Python module, installed into build/check-prefix (tests/)"
	@rm -rf build/check-prefix && $(MAKE) -s install PREFIX='$(CURDIR)/build/check-prefix' >build/check-install.log
	@PYTHONPATH=build/check-prefix/$(PYTHON_DIR) /usr/bin/python3 tests/python-api.py bin/tortuosity \
	  | tee build/python-api.log
check-pip-install: | $(TOOLS_test)
	@echo "== pip install of the package into a fresh virtual environment (tests/)"
	@bash tests/pip-install.sh bin/tortuosity '$(CURDIR)' | tee build/pip-install.log

# The same suite with AddressSanitizer and UndefinedBehaviorSanitizer; any report is fatal.
# The sanitizer build is also the baseline x86-64 build (no AVX2 clones of the hot loops): its
# end-to-end tests compare its output with bin/tortuosity's, byte for byte (REFERENCE).
SAN_FLAGS := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all \
             -DTORTUOSITY_BASELINE_ONLY
SAN_OBJ   := $(addprefix build/sanitize/,$(addsuffix .o,$(LIB_MODULES)))
SAN_CC     = $(CC) $(filter-out -O%,$(CFLAGS)) $(SAN_FLAGS)

build/sanitize/%.o: build/src/%.c $(HEADERS) Makefile | $(TOOLS_build)
	@mkdir -p $(dir $@)
	$(SAN_CC) -Ibuild/src $(HDF5_CFLAGS) -c -o $@ $<
build/sanitize/unit-tests: build/sanitize/unit-tests.o $(SAN_OBJ) build/sanitize/textbuf.o | $(TOOLS_build)
	$(SAN_CC) -o $@ $^ $(LDLIBS)
build/sanitize/tortuosity: $(addprefix build/sanitize/,$(addsuffix .o,$(CLI_MODULES))) $(SAN_OBJ) | $(TOOLS_build)
	$(SAN_CC) -o $@ $^ $(LDLIBS)

SANITIZE_SUITES := end-to-end unit-tests reliability
.PHONY: check-sanitize $(addprefix check-sanitize-,$(SANITIZE_SUITES))
check-sanitize $(addprefix check-sanitize-,$(SANITIZE_SUITES)): build/sanitize/unit-tests build/sanitize/tortuosity \
    bin/tortuosity $(TEST_LOCALE)
check-sanitize: | $(TOOLS_test)
	@$(call check_suites,$(addprefix check-sanitize-,$(SANITIZE_SUITES)))
	@$(call check_totals,check-sanitize,$(addprefix build/sanitize/,$(addsuffix .log,$(SANITIZE_SUITES))))
check-sanitize-unit-tests: | $(TOOLS_test)
	@echo "== unit tests, sanitized"
	@ASAN_OPTIONS=detect_leaks=1 ./build/sanitize/unit-tests | tee build/sanitize/unit-tests.log
check-sanitize-end-to-end: | $(TOOLS_test)
	@echo "== end-to-end checks, sanitized"
	@ASAN_OPTIONS=detect_leaks=1 DATA_DIR='$(DATA_DIR)' REFERENCE=bin/tortuosity \
	  bash tests/end-to-end.sh build/sanitize/tortuosity | tee build/sanitize/end-to-end.log
check-sanitize-reliability: | $(TOOLS_test)
	@echo "== reliability checks, sanitized"
	@ASAN_OPTIONS=detect_leaks=1 bash tests/reliability.sh build/sanitize/tortuosity | tee build/sanitize/reliability.log

# ---------------------------------------------------------------- fuzzing
# One libFuzzer harness per row of the format table, seeded from the real files; crashes land in
# build/fuzz/. The formats, their seeds (shell globs under DATA_DIR) and their longest inputs are
# the table's (tortuosity --list-formats): a new format is fuzzed without a line here.
FUZZ_SECONDS ?= 150
LIB_SOURCES  := $(addprefix build/src/,$(addsuffix .c,$(filter-out $(API_MODULES),$(LIB_MODULES))))
format_field  = ./bin/tortuosity --list-formats | awk -F'\t' -v f='$(1)' '$$1 == f { print $$$(2) }'

build/fuzz/fuzz-%: build/src/fuzz-readers.c $(LIB_SOURCES) $(HEADERS) | $(TOOLS_fuzz)
	@mkdir -p $(dir $@)
	clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -D_GNU_SOURCE \
	  -DFUZZ_FORMAT='"$*"' -Ibuild/src $(HDF5_CFLAGS) -o $@ $< $(LIB_SOURCES) $(LDLIBS)

# Seeds: the first bytes (up to the longest input) of up to twelve real files of the format.
# Shell globs, so that names with spaces stay whole. Plain text, legacy VTK, Slicer markups and
# ITK tubes, which the data do not have, are seeded below.
build/fuzz/corpus-vtk/.seeded: bin/tortuosity | $(TOOLS_test)
	@mkdir -p $(@D)
	/usr/bin/python3 tests/vtk-fixtures.py bin/tortuosity build/fuzz/vtk-fixtures >/dev/null
	cp build/fuzz/vtk-fixtures/legacy-*.vtk $(@D)/
	@touch $@
# Slicer markups and ITK tubes: the test's fixtures, written as those programs write them.
SEED_FIXTURES_mrk := mrk.json
SEED_FIXTURES_tre := tre
build/fuzz/corpus-mrk/.seeded build/fuzz/corpus-tre/.seeded: build/fuzz/corpus-%/.seeded: | $(TOOLS_test)
	@mkdir -p $(@D)
	/usr/bin/python3 tests/slicer-itk-fixtures.py build/fuzz/slicer-itk >/dev/null
	cp build/fuzz/slicer-itk/*.$(SEED_FIXTURES_$*) $(@D)/
	@touch $@
build/fuzz/corpus-text/.seeded: bin/tortuosity
	@mkdir -p $(@D)
	./bin/tortuosity phantom --shape salkowski --sigma 0.01 -o $(@D)/salkowski.txt
	./bin/tortuosity phantom --shape helix --count 3 --points 12 -o $(@D)/helices.txt
	@touch $@
build/fuzz/corpus-%/.seeded: data/manifest.tsv bin/tortuosity
	@mkdir -p $(@D)
	@globs=$$($(call format_field,$*,7)); max=$$($(call format_field,$*,8)); \
	shopt -s nullglob; files=(); for g in $$globs; do [ "$$g" = - ] || files+=('$(DATA_DIR)'/$$g); done; n=0; \
	for f in "$${files[@]:0:12}"; do head -c $$max "$$f" >$(@D)/seed-$$n; n=$$((n + 1)); done; \
	touch $@

# One run per reader; a crash stops with the input saved in build/fuzz/.
build/fuzz/%.log: build/fuzz/fuzz-% build/fuzz/corpus-%/.seeded
	@echo "fuzz $* for $(FUZZ_SECONDS) s"
	@./build/fuzz/fuzz-$* -max_total_time=$(FUZZ_SECONDS) -max_len=$$($(call format_field,$*,8)) \
	    -print_final_stats=1 -artifact_prefix=build/fuzz/crash-$*- build/fuzz/corpus-$* >$@.tmp 2>&1 \
	  || { tail -40 $@.tmp; echo "fuzz $*: crash, input saved in build/fuzz/"; exit 1; }
	@mv $@.tmp $@
	@grep -E 'stat::number_of_executed_units|stat::peak_rss_mb' $@ | sed "s/^/fuzz $*: /"

# The logs, one per row of the format table (expanded when the recipe runs, after bin/tortuosity).
FUZZ_LOGS = $(shell ./bin/tortuosity --list-formats 2>/dev/null | awk -F'\t' 'NR > 1 { print "build/fuzz/" $$1 ".log" }')
.PHONY: fuzz
fuzz: bin/tortuosity | $(TOOLS_build)
	@rm -f $(FUZZ_LOGS)
	@$(if $(FUZZ_LOGS),$(MAKE) --no-print-directory $(FUZZ_LOGS))

# ---------------------------------------------------------------- sharded runs
# One metrics run split into SHARDS parts by --shard, run by GNU parallel on JOBS local slots
# (or on the hosts of SSHLOGIN, which must see this directory at the same path), then joined
# with the header once; the joined file has the bytes of a single run. For a Slurm cluster,
# build/scripts/slurm-shards.sh does the same with a job array. parallel -q passes every word
# as it is: a file name may hold spaces, quotes or a ';'.
#   make sharded FILES='a.swc b.swc' [SHARDS=4] [JOBS=2] [SSHLOGIN=host1,host2] [SHARD_OPTIONS='-q']
SHARDS        ?= 4
JOBS          ?= 2
SHARD_DIR     ?= build/sharded
SHARD_OPTIONS ?= -q
.PHONY: sharded
sharded: bin/tortuosity | $(TOOLS_parallel)
	$(if $(strip $(FILES)),,$(error give the input files: make sharded FILES='...'))
	@[[ '$(SHARDS)' =~ ^[1-9][0-9]*$$ ]] || { echo "SHARDS must be a whole number >= 1, not '$(SHARDS)'" >&2; exit 2; }
	@mkdir -p '$(SHARD_DIR)' && rm -f '$(SHARD_DIR)'/shard-*.tsv '$(SHARD_DIR)'/all.tsv
	parallel -q --halt now,fail=1 --jobs $(JOBS) $(if $(SSHLOGIN),--sshlogin $(SSHLOGIN) --workdir $(CURDIR)) \
	  $(CURDIR)/bin/tortuosity metrics $(SHARD_OPTIONS) --shard {}/$(SHARDS) -o '$(SHARD_DIR)'/shard-{}.tsv \
	  $(FILES) ::: $$(seq $(SHARDS))
	awk 'FNR > 1 || NR == 1' '$(SHARD_DIR)'/shard-{1..$(SHARDS)}.tsv >'$(SHARD_DIR)'/all.tsv.part
	mv '$(SHARD_DIR)'/all.tsv.part '$(SHARD_DIR)'/all.tsv
	@echo "sharded: $(SHARD_DIR)/all.tsv"

# ---------------------------------------------------------------- lint, benchmark, clean
# make lint LINT_JUDGE=build/lint-uses.tsv judges the table of uses an earlier lint saved against the
# stages' packages as given now, without collecting the uses again (the end-to-end checks' case).
.PHONY: lint
# The targets whose rules the lint reads (make's dry run of them): every target a user runs, and
# the suites that check and check-sanitize run in a make of their own.
LINT_TARGETS := all check $(addprefix check-,$(CHECK_SUITES)) check-sanitize $(addprefix check-sanitize-,$(SANITIZE_SUITES)) \
                reproduce paper install uninstall bench bench-shards bench-stages memory fuzz sharded clean
lint: build/scripts/tools-lint.sh build/scripts/shell-commands.awk build/scripts/structure.sh $(CLI_OBJ) $(LIB_OBJ) \
      $(addprefix build/,$(filter %.sh,$(SCRIPTS))) \
    | $(foreach s,$(TOOL_STAGES),$(TOOLS_$(s)))
	@diff <(noroots paper.nw | sed 's/^<<\(.*\)>>$$/\1/' | sort) <(printf '%s\n' $(ROOTS) | sort) \
	  && echo "lint: chunk roots match the Makefile" \
	  || { echo "lint: roots of paper.nw ('<') differ from the Makefile ('>'); a misspelled chunk name?"; exit 1; }
	@METHOD='$(MODULES)' bash build/scripts/structure.sh paper.nw $(CLI_OBJ) $(LIB_OBJ)
	@bash build/scripts/tools-lint.sh \
	  $(if $(LINT_JUDGE),--judge '$(LINT_JUDGE)','$(MAKE)' build/scripts/shell-commands.awk build/lint-uses.tsv \
	    '$(LINT_TARGETS)') \
	  $(foreach s,$(TOOL_STAGES),'$(s)=$(PACKAGES_$(s))')

# The full BraVa set at the paper's rates, BENCH_RUNS times on one and on two threads: the wall
# time of each run and their median. Every run must give the bytes of the first.
BENCH_FILES = $(wildcard $(DATA_DIR)/brava-3darteryvis/allscans/*/*.swc)
BENCH_RUNS ?= 5
BENCH_SEGMENTS ?= 20000       # generated noisy helix arcs of ten points, for the cost model
BENCH_RUN   = ./bin/tortuosity metrics -q --rates $(RATE_LIST) --units mm $(BENCH_FILES)
# With BENCH_BASELINE=path/to/an/older/tortuosity: that program and this one in turn (A B A B) on two
# threads, BENCH_RUNS pairs, each pair's ratio and their median, and whether they give the same bytes.
.PHONY: bench bench-stages
bench: bin/tortuosity build/scripts/bench.sh build/scripts/quantile.awk build/scripts/median.awk build/scripts/segments.awk
	@RUNS=$(BENCH_RUNS) SEGMENTS=$(BENCH_SEGMENTS) RATES=$(RATE_LIST) BASELINE='$(BENCH_BASELINE)' \
	  bash build/scripts/bench.sh $(BENCH_FILES)

# What a shard costs: the whole run, and its first and last shard of 8, on two threads (BENCH_RUNS
# runs each, medians), on BENCH_SHARD_SEGMENTS generated ten-point segments in one plain-text file
# and on BraVa's SWC trees at the paper's rates; a shard should cost an eighth.
BENCH_SHARD_SEGMENTS ?= 200000
.PHONY: bench-shards
bench-shards: bin/tortuosity build/scripts/bench-shards.sh build/scripts/quantile.awk build/scripts/median.awk \
              build/scripts/segments.awk
	@RUNS=$(BENCH_RUNS) SEGMENTS=$(BENCH_SHARD_SEGMENTS) RATES=$(RATE_LIST) \
	  bash build/scripts/bench-shards.sh $(BENCH_FILES)

# Where one single-thread run of bench spends its time, stage by stage, per vessel and per output
# sample: perf samples with their call stacks, each given to the innermost stage on its stack.
bench-stages: bin/tortuosity build/scripts/bench-stages.awk | $(TOOLS_bench)
	@perf record -q -e cpu-clock -F 1000 --call-graph dwarf,16384 -o build/bench-stages.data \
	  $(BENCH_RUN) --jobs 1 >build/bench.tsv
	@perf script -i build/bench-stages.data -F ip,sym 2>/dev/null | awk -v hz=1000 \
	  -v vessels=$$(awk -F'\t' 'NR > 1 && !seen[$$1 FS $$2]++' build/bench.tsv | wc -l) \
	  -v samples=$$(awk -F'\t' 'NR > 1 { n += $$5 } END { print n }' build/bench.tsv) \
	  -f build/scripts/bench-stages.awk
	@rm -f build/bench-stages.data

# Peak memory of metrics on 10^4, 10^5 and 10^6 two-point vessels (one text file each): it should
# stay flat, set by one file's bytes and one window of vessels, not by their number. Then one vessel
# of 10^6 points (three turns of a helix of radius 5 mm and pitch 10 mm: curvature 0.1816 and torsion
# 0.0578 per mm) at the four rates, 10^8 samples at 100X: measured in pieces, it must be ok at every
# rate within MEMORY_LONG_LIMIT_KB.
MEMORY_SIZES := 10000 100000 1000000
MEMORY_LONG_POINTS := 1000000
MEMORY_LONG_LIMIT_KB := 524288
.PHONY: memory
memory: bin/tortuosity build/scripts/memory.sh | $(TOOLS_bench)
	@SIZES='$(MEMORY_SIZES)' LONG_POINTS=$(MEMORY_LONG_POINTS) LIMIT_KB=$(MEMORY_LONG_LIMIT_KB) RATES=$(RATE_LIST) \
	  bash build/scripts/memory.sh

.PHONY: clean
clean:
	rm -rf bin build/src build/obj build/scripts build/results build/sanitize build/fuzz build/unit-tests \
	  build/*.log build/paper.* build/*.tsv build/*.tex

# ---------------------------------------------------------------- tools
# The Debian packages of each stage. A rule that runs a stage's programs names the stage's stamp,
# $(TOOLS_stage), as an order-only prerequisite; the stamp installs the packages (as root; otherwise
# it prints the one apt-get line to run) and is remade when this Makefile changes. Every stage has
# the build stage's packages too. 'make lint' checks that each program, Python module and LaTeX
# package a recipe or test uses comes from its stage's packages (scripts/tools-lint.sh).
PACKAGES_build    := make gcc libc6-dev binutils git noweb libgsl-dev libexpat1-dev libjansson-dev zlib1g-dev liblz4-dev \
                     liblzma-dev libssl-dev \
                     libhdf5-dev pkg-config
PACKAGES_report   := gnuplot-nox r-base-core texlive-latex-base texlive-latex-recommended \
                     texlive-fonts-recommended lmodern poppler-utils
# What the end-to-end checks compare with: VTK's own readers (and its rendering, in Xvfb), h5py's
# files, pandas and R for the provenance sidecar, man for the manual page, GNU time for peak memory,
# pip and venv for the Python package.
PACKAGES_test     := python3-vtk9 python3-pandas python3-numpy python3-h5py r-base-core man-db groff-base time \
                     locales strace python3-venv python3-pip python3-setuptools python3-wheel xvfb xauth \
                     r-cran-mgcv r-cran-pracma
PACKAGES_fuzz     := clang libclang-rt-14-dev
PACKAGES_bench    := linux-perf time
PACKAGES_parallel := parallel
# The authors' R code (make peers): R and the CRAN packages it loads, as Debian packages.
PACKAGES_peers    := r-base-core r-cran-mgcv r-cran-pracma

# $(call ensure_packages,PACKAGES): install those of PACKAGES that dpkg does not list as installed.
define ensure_packages
missing=; for p in $(1); do \
  dpkg-query -W -f='$${db:Status-Abbrev}' $$p 2>/dev/null | grep -q '^ii' || missing="$$missing $$p"; done; \
if [ -n "$$missing" ]; then \
  if [ "$$(id -u)" = 0 ]; then \
    echo "missing packages:$$missing; installing them"; \
    apt-get update -qq; \
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing >/dev/null; \
  else \
    echo "missing packages:$$missing. Install them with:"; \
    echo "  sudo apt-get install$$missing"; \
    exit 1; \
  fi; \
fi
endef

build/.tools-%: Makefile
	@mkdir -p build
	@$(call ensure_packages,$(PACKAGES_$*))
	@touch $@
$(addprefix build/.tools-,$(filter-out build,$(TOOL_STAGES))): | $(TOOLS_build)
