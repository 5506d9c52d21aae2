# Quick start on a fresh Debian 12 machine (as root, or with sudo):
#   make demo   install what is missing, build, install, and run the demo (out/demo) from the
#               build tree (build/bin/spt-python): SPT, VTK's projected tetrahedra and HAVS-like
#               against the exact reference on interpenetrating volumes and on a drill of 10^6
#               tetrahedra
#   make pictures  the README's pictures (Documentation/images), from the build tree
#   make test   the same set-up, then every test (ctest, which also runs the Python tests)
#   make test-egl  without X (no Xvfb, no DISPLAY): the tests of what differs there (ctest label
#               egl: the EGL window, and each mapper against the exact reference in it);
#               TESTS=. runs every test through EGL
#   make test-debian13  make test on Debian 13 (trixie) in a debootstrap root file system
#               (.ci/debian-root; kept in DEBIAN13_CACHE, default /var/cache/spt/debian13)
#   make test-debian-unstable  the same on Debian unstable (sid: ParaView 6, VTK 9.4 or later;
#               kept in DEBIAN_UNSTABLE_CACHE, default /var/cache/spt/debian-sid)
#   make test-vtk-wheel  the C++ module and tests built against PyPI's VTK wheel (vtk 9.5.0) and
#               run without X (.ci/vtk-wheel-sdk; kept in VTK_WHEEL_CACHE, default
#               /var/cache/spt/vtk-sdk); make build-vtk-wheel stops after the build
#   make wheel  the Python wheel (dist/spt_volume-*.whl) against PyPI's vtk 9.5 (.ci/wheel:
#               scikit-build-core, VTK's wrapping tools built from ../shared/third_party; kept in
#               WHEEL_CACHE, default /var/cache/spt/wheel), one per CPython of WHEEL_PYTHONS
#   make test-wheel  the wheels, then pip install of each (with vtk and pyvista from PyPI) in a
#               fresh virtual environment of its Python without Debian's VTK, and its tests there
#               without X
#   make test-jupyter  SPT in a JupyterLab notebook in headless Chromium (.ci/jupyter): the wheel
#               of dist/ (built by make wheel if missing) with pyvista[jupyter] in a fresh virtual
#               environment (kept in JUPYTER_CACHE, default /var/cache/spt/jupyter), its image
#               against the exact reference before and after a drag; screenshots in out/jupyter
#   make sanitize  the C++ tests built with AddressSanitizer and UndefinedBehaviorSanitizer
#   make lint   the same set-up, then the format and lint checks: flake8 on the Python
#               (.flake8), clang-format on every C++ file (.clang-format), and files of at most
#               600 lines with functions of at most 60 (Utilities/check_lengths.py)
#   make bench-compare BASE=<git ref>  the race of this tree and of BASE, each built in its
#               own tree, raced alternately (SCENES, RUNS, SIZE): out/bench-compare/compare.json
#
# Variables: PREFIX (install prefix, default /usr/local), BUILD (build directory, default
# build), JOBS (parallel build jobs and tests, default: number of cores), DEMO_OUTPUT (where the demo
# writes its images and tables, default out/demo), TESTS (a regular expression: test,
# test-egl and test-debian13 run only the tests whose names match, e.g. TESTS=paraview_mpi),
# WHEEL_PYTHONS (the CPython interpreters that make wheel and test-wheel build and test a wheel
# for, one each, default /usr/bin/python3; e.g. WHEEL_PYTHONS="/usr/bin/python3
# ~/.pyenv/versions/3.13.0/bin/python3.13" for cp311 and cp313), SPT_DATA_DIR (the folder of
# the real data sets that the demo, the pictures and the tests read; default: none, and the
# tests that need one skip).

PREFIX ?= /usr/local
BUILD ?= build
DEMO_OUTPUT ?= $(CURDIR)/out/demo
JOBS ?= $(shell nproc)
TESTS ?=
CTEST = ctest -j$(JOBS) --output-on-failure --timeout 1500 $(if $(TESTS),-R '$(TESTS)')
PYTHON := /usr/bin/python3
# The VTK inside Debian's ParaView (5.11 on Debian 12, 5.13 on Debian 13), found once paraview-dev
# is installed (a recursive variable: evaluated when a recipe runs, after deps); where ParaView
# has none of its own (Debian's ParaView 6 is built on Debian's VTK), Debian's VTK.
VTK_DIR ?= $(strip $(or $(lastword $(shell ls -d /usr/lib/*/cmake/paraview-*/vtk 2>/dev/null \
	| sort -V)),$(lastword $(shell ls -d /usr/lib/*/cmake/vtk-* 2>/dev/null | sort -V))))
XVFB := xvfb-run -a -s "-screen 0 1280x1024x24 -noreset"
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

# ParaView brings the VTK SDK (Debian 12: ParaView 5.11, VTK 9.2; Debian 13: ParaView 5.13,
# VTK 9.3); the -dev packages are what its CMake package looks for for the modules this project
# uses. Every name is the same on Debian 12 and 13 but TetGen's, which carries its version:
# the newest libtetX.Y-dev that apt knows.
TETGEN_PACKAGE = $(or $(lastword $(shell apt-cache pkgnames libtet 2>/dev/null \
	| grep -E '^libtet[0-9.]+-dev$$' | sort -V)),libtet1.5-dev)
# Debian's ParaView 6 is built on Debian's VTK (paraview depends on libvtkX.Y) instead of a VTK of
# its own, and paraview-dev does not bring VTK's SDK: libvtk9-dev then.
VTK_PACKAGE = $(if $(shell apt-cache depends paraview 2>/dev/null \
	| grep -E 'Depends: libvtk[0-9.]+$$'),libvtk9-dev)
PACKAGES = cmake ninja-build g++ make \
	paraview paraview-dev python3-paraview $(VTK_PACKAGE) \
	openmpi-bin libopenmpi-dev libglew-dev libx11-dev libgl-dev libegl-dev libpng-dev libjpeg-dev libtiff-dev \
	zlib1g-dev libfreetype-dev libexpat1-dev liblz4-dev liblzma-dev libxml2-dev \
	libdouble-conversion-dev libutfcpp-dev libpython3-dev \
	$(TETGEN_PACKAGE) libglm-dev \
	python3-numpy python3-scipy python3-matplotlib python3-pytest python3-venv \
	xvfb xauth libgl1-mesa-dri \
	clang-format flake8

.PHONY: all deps debian-root-deps configure build install demo pictures test test-egl test-debian13 \
	test-debian-unstable \
	build-vtk-wheel test-vtk-wheel wheel test-wheel jupyter-deps test-jupyter sanitize lint bench-compare clean

all: build

# Install those of the packages $(1) that are missing, with apt.
define install_missing
	@missing=$$(for p in $(1); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q "install ok installed" || echo $$p; \
	done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing:" $$missing; \
	  $(SUDO) apt-get update -q && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -q --no-install-recommends $$missing; \
	else echo "All packages present."; fi
endef

deps:
	$(call install_missing,$(PACKAGES))
	@# Debian 13: ParaView's CMake files name its Python modules without their suffix.
	@for d in /usr/lib/*/cmake/paraview-*; do CMake/link-vtk-python-modules "$$d"; done

configure: deps
	cmake -S . -B $(BUILD) -G Ninja \
	  -DCMAKE_BUILD_TYPE=Release \
	  -DCMAKE_INSTALL_PREFIX=$(PREFIX) \
	  -DVTK_DIR=$(VTK_DIR) \
	  -DPython3_EXECUTABLE=$(PYTHON) \
	  -DBUILD_SHARED_LIBS=ON \
	  -DSPT_DATA_DIR="$(SPT_DATA_DIR)"

build: configure
	cmake --build $(BUILD) -j $(JOBS)

install: build
	$(SUDO) cmake --install $(BUILD)
	$(SUDO) ldconfig

# The demo and the pictures are experiments, which the build tree holds and an install does not:
# its interpreter runs them (the package and libraries of the build tree).
SPT_PYTHON = $(abspath $(BUILD))/bin/spt-python

demo: install
	cd /tmp && $(XVFB) $(SPT_PYTHON) -m spt demo --output $(abspath $(DEMO_OUTPUT))

pictures: install
	cd /tmp && $(XVFB) $(SPT_PYTHON) -m spt figures readme --output $(CURDIR)/Documentation/images \
	  --bench $(CURDIR)/Documentation/bench/bench.json

test: install
	cd $(BUILD) && SPT_TEST_INSTALLED=1 $(XVFB) $(CTEST)

# Without X: no Xvfb and no DISPLAY, so that every window is the EGL window
# (vtkHeadlessEGLRenderWindow). By default the tests labelled egl, those that say something new
# there (the window itself, the old-context refusal, each mapper against the exact reference);
# TESTS= chooses others (TESTS=. all of them). What needs X skips, saying so: ParaView's tests
# (its windows are GLX only) and the comparison of an EGL image with an X one.
test-egl: install
	cd $(BUILD) && env -u DISPLAY -u XAUTHORITY SPT_TEST_INSTALLED=1 \
	  $(CTEST) $(if $(TESTS),,-L egl); status=$$?; \
	  echo "Skipped without X:"; grep -h '^SKIPPED' Testing/Temporary/LastTest.log; exit $$status

# What .ci/debian-root needs on the host beyond `deps` (only the Debian root targets use it).
ROOT_PACKAGES = debootstrap
debian-root-deps:
	$(call install_missing,$(ROOT_PACKAGES))

# `make test` on Debian 13 in a root file system made with debootstrap (needs root and
# debootstrap): the base system, apt's packages and the build directory are kept in
# DEBIAN13_CACHE between runs; see .ci/debian-root.
DEBIAN13_CACHE ?= /var/cache/spt/debian13
test-debian13: debian-root-deps
	$(SUDO) env SPT_DEBIAN_CACHE=$(DEBIAN13_CACHE) JOBS=$(JOBS) \
	  SPT_DEBIAN_TARGET="test$(if $(TESTS), TESTS='$(TESTS)')" \
	  $(if $(SPT_DATA_DIR),SPT_DATA_DIR=$(SPT_DATA_DIR)) .ci/debian-root trixie

# The same on Debian unstable (sid), whose ParaView and VTK are the newest Debian has (ParaView
# 6.1 and VTK 9.6 when this was written): the glad branch of the OpenGL loader (VTK 9.4 on)
# built and run. DEBIAN_UNSTABLE_TARGET=build stops after the build.
DEBIAN_UNSTABLE_CACHE ?= /var/cache/spt/debian-sid
DEBIAN_UNSTABLE_TARGET ?= test
test-debian-unstable: debian-root-deps
	$(SUDO) env SPT_DEBIAN_CACHE=$(DEBIAN_UNSTABLE_CACHE) JOBS=$(JOBS) \
	  SPT_DEBIAN_TARGET=$(DEBIAN_UNSTABLE_TARGET) \
	  $(if $(SPT_DATA_DIR),SPT_DATA_DIR=$(SPT_DATA_DIR)) .ci/debian-root sid

# The C++ module and its C++ tests against the VTK of PyPI's wheel (vtk) with Kitware's SDK
# (vtk-sdk) of the same version, pointed at the wheel's Linux libraries (.ci/vtk-wheel-sdk): the
# glad loader and the VTK API of 9.5 without a Debian that ships them. No Python package (the
# SDK's wrapping tools are macOS programs; the wheel below builds VTK's tools from source) and
# no ParaView plugin. The tests run without X: every window is the EGL window.
VTK_WHEEL_VERSION ?= 9.5.0
VTK_WHEEL_CACHE ?= /var/cache/spt/vtk-sdk
build-vtk-wheel: deps
	SPT_VTK_WHEEL_CACHE=$(VTK_WHEEL_CACHE) SPT_VTK_WHEEL_BUILD=$(VTK_WHEEL_CACHE)/build-$(VTK_WHEEL_VERSION) \
	  JOBS=$(JOBS) .ci/vtk-wheel-sdk $(VTK_WHEEL_VERSION)

test-vtk-wheel: build-vtk-wheel
	cd $(VTK_WHEEL_CACHE)/build-$(VTK_WHEEL_VERSION) && env -u DISPLAY -u XAUTHORITY \
	  nice -n 15 ctest --output-on-failure --timeout 1500

# The Python wheel (pyproject.toml) against the vtk wheel of VTK_WHEEL_VERSION, whose SDK
# .ci/vtk-wheel-sdk prepares in VTK_WHEEL_CACHE; test-wheel installs it in a fresh virtual
# environment and runs Testing/Wheel and the package's own tests there (.ci/wheel). One wheel
# per CPython of WHEEL_PYTHONS (interpreters, default Debian's), each against the vtk wheel of
# the same Python and tested in an environment of that interpreter. The wheels for vtk 9.5 go
# to dist/, those for another vtk release to dist/vtk-<release>/ (the file names are the same);
# a release after 9.5 is built from VTK's source (SPT_VTK_SOURCE, .ci/wheel).
WHEEL_CACHE ?= /var/cache/spt/wheel
WHEEL_PYTHONS ?= $(PYTHON)
WHEEL_OUTPUT = $(CURDIR)/dist$(if $(filter 9.5.%,$(VTK_WHEEL_VERSION)),,/vtk-$(VTK_WHEEL_VERSION))
WHEEL_ENV = SPT_VTK_WHEEL_CACHE=$(VTK_WHEEL_CACHE) SPT_WHEEL_CACHE=$(WHEEL_CACHE) \
	VTK_WHEEL_VERSION=$(VTK_WHEEL_VERSION) JOBS=$(JOBS) SPT_WHEEL_OUTPUT=$(WHEEL_OUTPUT)
wheel: deps
	@for python in $(WHEEL_PYTHONS); do \
	  echo "make wheel: $$python"; SPT_WHEEL_PYTHON=$$python $(WHEEL_ENV) .ci/wheel || exit 1; \
	done

test-wheel: deps
	@for python in $(WHEEL_PYTHONS); do \
	  echo "make test-wheel: $$python"; \
	  SPT_WHEEL_PYTHON=$$python $(WHEEL_ENV) .ci/wheel --test || exit 1; \
	done

# The notebook test's browser: Debian's Chromium and its WebDriver (Selenium comes from PyPI).
JUPYTER_PACKAGES = chromium chromium-driver
JUPYTER_CACHE ?= /var/cache/spt/jupyter
jupyter-deps:
	$(call install_missing,$(JUPYTER_PACKAGES))

# The wheel of Debian's Python from dist/ (make wheel builds it where it is missing; after a
# change, make wheel first) in a notebook: .ci/jupyter.
test-jupyter: deps jupyter-deps
	@tag=$$($(PYTHON) -c 'import sys; print("cp%d%d" % sys.version_info[:2])'); \
	  ls dist/spt_volume-*-$$tag-$$tag-*.whl >/dev/null 2>&1 || $(MAKE) wheel WHEEL_PYTHONS=$(PYTHON)
	SPT_WHEEL_PYTHON=$(PYTHON) SPT_JUPYTER_CACHE=$(JUPYTER_CACHE) SPT_WHEEL_OUTPUT=$(CURDIR)/dist \
	  .ci/jupyter

# The C++ tests (the Python tests would need a sanitized interpreter) under ASan and UBSan.
# Reports inside Mesa, X11 and VTK's own libraries are suppressed in Testing/Sanitizers;
# anything in this project's code fails the run.
SANITIZE_FLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
sanitize: deps
	cmake -S . -B $(BUILD)-sanitize -G Ninja \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DVTK_DIR=$(VTK_DIR) \
	  -DPython3_EXECUTABLE=$(PYTHON) \
	  -DSPT_WRAP_PYTHON=OFF \
	  -DCMAKE_CXX_FLAGS="$(SANITIZE_FLAGS)" \
	  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
	  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined"
	cmake --build $(BUILD)-sanitize -j $(JOBS)
	cd $(BUILD)-sanitize && \
	  ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/Testing/Sanitizers/lsan.supp:print_suppressions=0 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions=$(CURDIR)/Testing/Sanitizers/ubsan.supp \
	  $(XVFB) ctest --output-on-failure --timeout 1500

# Every C++ source and header of the project, wherever it is (build trees left out).
CXX_SOURCES = $(shell find Rendering Meshing Plugin Testing \( -name '*.h' -o -name '*.cxx' \
	-o -name '*.c' \) -not -path '*/build*' | sort)

lint: deps
	flake8 .
	clang-format --dry-run -Werror $(CXX_SOURCES)
	$(PYTHON) Utilities/check_lengths.py
	$(PYTHON) -m pytest -q -p no:cacheprovider Utilities/Testing/test_check_lengths.py

# The race of the current tree (the head) against that of BASE, side by side on this machine
# (Utilities/BenchCompare): both built alike, each in a build tree of its own under
# out/bench-compare and run from it, then RUNS races of each, alternately, of the scenes SCENES
# (which must exist in both) at SIZE x SIZE; compare.json and a table of SPT's time to VTK PT's
# error, head over base. Scenes other than the generated drill-* read SPT_DATA_DIR.
BASE ?=
SCENES ?= spx,bluntfin
RUNS ?= 2
SIZE ?= 256
bench-compare: deps
	@test -n "$(BASE)" || { echo "make bench-compare: BASE=<git ref> is required" >&2; exit 2; }
	$(XVFB) $(PYTHON) Utilities/BenchCompare/bench_compare.py --base '$(BASE)' \
	  --scenes '$(SCENES)' --runs $(RUNS) --size $(SIZE) --jobs $(JOBS) --vtk-dir $(VTK_DIR) \
	  --python $(PYTHON) --output $(CURDIR)/out/bench-compare

clean:
	rm -rf $(BUILD) $(BUILD)-sanitize out dist
