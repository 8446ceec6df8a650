# The front door. `make reproduce` (quick scale) and `make test` work on a fresh Debian machine:
# both install what is missing first (`make deps`, apt-get, idempotent).
BUILD      ?= build
BUILD_CUDA ?= build-cuda
SCALE      ?= quick
# SITTING=SECONDS: the wall time one sitting of full-scale runs may take (they continue next time)
PY         := /usr/bin/python3
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=

# Debian packages the project needs (Thrust comes from the CUDA toolkit when it is installed,
# else from Debian's libthrust-dev).
DEBS := cmake make g++ ccache libomp-dev libeigen3-dev libopenblas-openmp-dev libfftw3-dev libhypre-dev libhdf5-dev libyaml-cpp-dev libcli11-dev libgtest-dev googletest \
        libopenmpi-dev openmpi-bin libfftw3-mpi-dev \
        python3 python3-matplotlib python3-numpy python3-yaml python3-h5py python3-venv
THRUST_FROM_CUDA := $(wildcard /usr/local/cuda/targets/x86_64-linux/include/cccl/thrust/version.h /usr/local/cuda/include/thrust/version.h)
ifeq ($(strip $(THRUST_FROM_CUDA)),)
DEBS += libthrust-dev libcub-dev
endif
NVCC := $(firstword $(wildcard /usr/local/cuda/bin/nvcc) $(shell command -v nvcc 2>/dev/null))

.PHONY: help deps configure build test test-unit check-cuda build-cuda gpu-check gpu-bundle reproduce reproduce-% keep-% point-sets clean

help:
	@echo "make reproduce          every implemented study at SCALE=$(SCALE) -> reports/"
	@echo "make reproduce-NAME     one study or chapter (appendixA, chapter2, ...), e.g. SCALE=full SITTING=3600"
	@echo "make keep-NAME          copy a full-scale run's checkpoints into kept/NAME/full (commit them to continue elsewhere)"
	@echo "make test               install deps, build, run every test (unit, harness, studies at quick scale)"
	@echo "make build-cuda         configure and build the CUDA backend (nvcc)"
	@echo "make gpu-check          on a machine with an NVIDIA GPU: CUDA build, unit tests on the device, GPU benchmarks -> reports/gpu"
	@echo "make gpu-bundle         the CUDA build's tests and GPU-check drivers with their libraries, for a GPU node without the build's dependencies"
	@echo "make deps               install missing Debian packages"
	@echo "make point-sets         regenerate reference/point_sets (maximal-determinant-like sites; ~1 h on 2 cores)"

deps:
	@missing=""; for p in $(DEBS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "deps: installing$$missing"; \
	  if [ "$$(id -u)" = 0 ]; then SUDO=""; else SUDO=sudo; fi; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing >/dev/null \
	    || { echo "deps: apt-get install failed for:$$missing"; exit 1; }; \
	else echo "deps: all present"; fi
	@# VTK's XDMF reader, for the test that opens a run's XDMF as ParaView does: Debian's
	@# python3-vtk9 is built without it, so the VTK wheel from PyPI goes into a venv.
	@[ -x .venv-vtk/bin/python ] || { echo "deps: VTK (PyPI wheel) into .venv-vtk"; $(PY) -m venv .venv-vtk && \
	  .venv-vtk/bin/pip install -q 'vtk>=9.2' || { echo "deps: pip install vtk failed"; rm -rf .venv-vtk; exit 1; }; }

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DRBFIB_PYTHON=$(PY) $(CMAKE_ARGS) >/dev/null

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test-unit: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L "unit|harness"

# The CUDA backend must compile wherever nvcc is installed (GPU or not); it runs only on a GPU.
check-cuda: deps
	@if [ -n "$(NVCC)" ]; then $(MAKE) --no-print-directory build-cuda; \
	else echo "check-cuda: no nvcc on this machine, CUDA build skipped"; fi

build-cuda:
	cmake -S . -B $(BUILD_CUDA) -DRBFIB_BACKEND=CUDA -DCMAKE_CUDA_COMPILER=$(NVCC) -DRBFIB_PYTHON=$(PY) $(CMAKE_ARGS) >/dev/null
	cmake --build $(BUILD_CUDA) -j $(JOBS)

# On a machine with an NVIDIA GPU, one call: the CUDA backend built, its unit tests run on the
# device, then the benchmarks (bench_ib, bench_cells, bench_fluid) and the whole-blood step
# (chapter4_cells) at quick scale, their reports in reports/gpu/<study> naming the GPU. Without a
# GPU it says so and exits 2 (the CUDA build itself is compiled by `make test`).
gpu-check: deps
	@command -v nvidia-smi >/dev/null 2>&1 && nvidia-smi -L 2>/dev/null | grep -q "GPU" \
	  || { echo "gpu-check: no NVIDIA GPU on this machine (nvidia-smi -L lists none)"; exit 2; }
	@[ -n "$(NVCC)" ] || { echo "gpu-check: no nvcc on this machine (the CUDA toolkit is needed)"; exit 2; }
	@nvidia-smi -L
	$(MAKE) --no-print-directory build-cuda
	cd $(BUILD_CUDA) && ctest --output-on-failure -j $(JOBS) -L unit
	@failed=""; for s in bench_ib bench_cells bench_fluid chapter4_cells; do \
	  $(PY) -m harness run $$s --build $(BUILD_CUDA) --reports reports/gpu --out runs/gpu || failed="$$failed $$s"; done; \
	if [ -n "$$failed" ]; then echo "gpu-check: failed checks in:$$failed (reports/gpu)"; exit 1; fi

# For a GPU node without the build's dependencies: tools/gpu_check_bundle.sh runs the same check there.
gpu-bundle: build-cuda
	tools/gpu_bundle.sh $(BUILD_CUDA)

test: build check-cuda
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

reproduce: build
	$(PY) -m harness run all --scale $(SCALE) --build $(BUILD) $(if $(SITTING),--sitting $(SITTING))

reproduce-%: build
	$(PY) -m harness run $* --scale $(SCALE) --build $(BUILD) $(if $(SITTING),--sitting $(SITTING))

# Copies a full-scale run's checkpoints into kept/NAME/full (to commit): a full run elsewhere continues from them.
keep-%:
	$(PY) -m harness keep $*

# The stored evaluation sites of the Chapter 3 study: N = 22, 44, 67 (n = 529, 2025, 4624).
POINT_SET_DEGREES := 22 44 67
point-sets: build
	@for N in $(POINT_SET_DEGREES); do \
	  $(BUILD)/bin/max_determinant_points --degree $$N --out reference/point_sets/max_determinant_N$$N.txt || exit 1; \
	done

clean:
	rm -rf $(BUILD) $(BUILD_CUDA) runs
