# subcontact: `make cylinder` runs the paper's example, `make test` the suite.
# Both install what they need first (`make deps`): the gmsh CLI (Debian) and
# meshio (pip, used by the tests to open the VTU files).

CARGO   ?= cargo
BIN     := target/release/subcontact
PYTHON  ?= python3

.PHONY: all deps deps-mpi deps-strace build lint cylinder tunnel tunnel-joints footing footing-layers dam blocks3d dam3d dam3d-joints tunnel3d rockmass wedge safety slope water test test-mpi fuzz bench bench3d bench-blocks bench-ccx bench-interface scaling stress stress-open clean

all: build

deps:
	@command -v gmsh >/dev/null 2>&1 || { \
	  echo "gmsh CLI not found: installing it with apt-get (Debian package gmsh)"; \
	  if command -v apt-get >/dev/null 2>&1; then \
	    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gmsh >/dev/null) || \
	    { echo "error: could not install gmsh; run 'apt-get install -y gmsh' as root (or install gmsh 4.x so that 'gmsh' is on PATH)"; exit 1; }; \
	  else echo "error: gmsh is missing and apt-get is not available: install gmsh 4.x so that 'gmsh' is on PATH"; exit 1; fi; }
	@$(PYTHON) -c "import meshio" >/dev/null 2>&1 || $(PYTHON) -m pip install -q meshio || \
	  { echo "error: could not install the Python package meshio (pip install meshio)"; exit 1; }

build:
	$(CARGO) build --release

# The paper's example: the fine default mesh and the paper's own 30-hex mesh,
# with Tables 1 and 2 side by side in results/cylinder/report.md.
cylinder: deps build
	$(BIN) paper geo/cylinder.toml geo/cylinder_paper.toml

# A stiff foundation beam on elastic ground under an eccentric column load
# (e = B/3): the far edge lifts off; contact pressure and gaps in
# results/footing/ (footing_contact.vtu, contact.csv, report.md).
footing: deps build
	$(BIN) solve geo/footing.toml

# A square footing on two soil layers of prisms (a triangulated plan
# extruded in layers), loaded near one corner: the opposite corner lifts
# (results/footing_layers/: plan_base.png by state and sigma_n, contact.csv).
footing-layers: deps build
	$(BIN) solve geo/footing_layers.toml

# A tunnel lining in rock against Einstein & Schwartz (1979): no slip and
# full slip; thrust and moment tables in results/tunnel{,_slip}/report.md.
tunnel: deps build
	$(BIN) solve geo/tunnel.toml --quiet
	$(BIN) solve geo/tunnel_slip.toml --quiet
	@for r in tunnel tunnel_slip; do echo; echo "results/$$r/report.md:"; \
	  awk '/^## Lining/{p=1} p{print} p&&/^Largest error/{exit}' results/$$r/report.md; done

# A tunnel in rock cut by three joint sets into ~150 blocks (one body
# group, one contact group per set), in-situ stress, bare opening: which
# blocks loosen in the crown (results/tunnel_joints/report.md: the contact
# groups and the most mobilised block faces; faces.csv).
tunnel-joints: deps build
	$(BIN) solve geo/tunnel_joints.toml

# A gravity dam of three blocks on rock: self-weight, then the reservoir in
# two steps; the heel opens (results/dam/, dam.pvd for the steps). Then the
# same dam with the water under it (geo/dam_uplift.toml): the reservoir at
# 42 m, uplift through a drain line, the heel's crack filled with the
# reservoir's water, and the base's factor of safety (results/dam_uplift/).
dam: deps build
	$(BIN) solve geo/dam.toml
	$(BIN) solve geo/dam_uplift.toml

# A block pressed onto a block and pushed along x, in 3D on tet10: the
# trailing edge slips (results/blocks3d/: plan views of the joint by state
# and sigma_n in report.md).
blocks3d: deps build
	$(BIN) solve geo/blocks3d.toml

# A gravity-dam slice in 3D: three blocks on rock, joints ending on the base;
# self-weight, then the reservoir in two steps (results/dam3d/); then with
# uplift, drains and the heel's crack filling, and the base's factor of
# safety (geo/dam3d_uplift.toml, results/dam3d_uplift/; about 20 s).
dam3d: deps build
	$(BIN) solve geo/dam3d.toml
	$(BIN) solve geo/dam3d_uplift.toml

# A gravity dam in 3D whose contraction joints cross its lift joints: three
# monoliths in a stepped valley, each cut into three lifts by a horizontal
# joint set ([[joint_sets]] "lifts"); self-weight, then the reservoir in two
# steps (results/dam3d_joints/: joints.png with every joint by state, the
# contact groups and block faces in report.md).
# Then with the water under the base (geo/dam3d_joints_uplift.toml): the
# reservoir at 42 m, uplift through a drain line, cracks filling each in
# its own sheet of the base (results/dam3d_joints_uplift/; about 30 s).
dam3d-joints: deps build
	$(BIN) solve geo/dam3d_joints.toml
	$(BIN) solve geo/dam3d_joints_uplift.toml

# A tunnel in 3D through three oblique joint sets by dip / dip direction
# ([[joint_sets]]): the tool cuts the box minus the opening into about 150
# blocks; in-situ stress, bare opening: which blocks loosen round it
# (results/tunnel3d/: stereonet.png, joints.png, blocks.csv, report.md).
tunnel3d: deps build
	$(BIN) solve geo/tunnel3d.toml

# A jointed rock mass: a 10 m cube and three joint sets by orientation and
# spacing ([[joint_sets]]), which the tool cuts into 64 blocks (hex20,
# `structured`); gravity, then pressure and shear on top: joints slip and
# open near the top (results/rockmass_sets/: joints.png, plan_*.png,
# faces.csv, report.md). geo/rockmass.toml is the same rock mass built by
# hand in the .geo, which the benchmarks scale up.
rockmass: deps build
	$(BIN) solve geo/rockmass_sets.toml

# A rock wedge in a V-groove (Hoek & Bray) under its weight, then its factor
# of safety against sliding by strength reduction of the joints ([safety]):
# results/wedge/ (report.md, safety_*.png, summary.json "safety").
wedge: deps build
	$(BIN) solve geo/wedge.toml

# The factor of safety and the load factor beside the closed forms, the
# mechanism named (docs/safety.md): the wedge in a V-groove on two meshes
# against Hoek & Bray's rigid block (and with water on its planes), Hoek & Bray's planar slope with
# cohesion, the gravity dam against its base's resultants by hand (also
# with a cohesive base), Goodman & Bray's toppling block in 2D and 3D, the
# gravity wall's overturning and sliding load factors; the tables in
# results/safety/safety.md. About a minute.
safety: deps build
	$(PYTHON) scripts/safety/safety.py

# A rock slope with water in its tension crack and on its sliding plane
# (Hoek & Bray's planar failure): self-weight, then the water; its factor
# of safety with the water held (results/slope/: report.md, the water on
# the plane in interfaces.svg and contact.csv).
slope: deps build
	$(BIN) solve geo/slope.toml

# Water in the joints beside the closed forms (scripts/water/water.py): the
# slope dry, with V, with U and V; the wedge with water on its planes; the
# dam undrained, drained, under k_h = 0.1 with Westergaard, its heel crack
# against USACE; the joint's water against two loaded faces. One line per
# case; results/water/water.md. About 20 s.
water: deps build
	$(PYTHON) scripts/water/water.py

# Run time against error on the cylinder, orders 1 and 2, up to ~2.6e6 DOFs:
# results/cylinder/bench.{csv,md,svg}.
bench: deps build
	$(BIN) bench geo/cylinder.toml --orders 1,2 --levels 7 --start 0.4 --max-dofs 3000000

# Run time against error in 3D (docs/bench3d.md): block on block in partial
# slip on structured hex8/hex20 (up to 1.1e5 DOFs), on unstructured tet4/tet10
# (up to 2e5 DOFs) and on the hex27 meshes of issue 10's table:
# results/bench3d/{hex,tet,hex27}/bench.{csv,md,svg}. About 2 minutes.
bench3d: deps build
	$(BIN) bench geo/blocks3d_hex.toml --orders 1,2 --levels 4 --start 0.25 --max-dofs 150000 --out results/bench3d/hex
	$(BIN) bench geo/blocks3d.toml --orders 1,2 --levels 3 --start 0.2 --max-dofs 250000 --out results/bench3d/tet
	$(BIN) bench scripts/bench3d/blocks3d_hex27.toml --orders 2 --levels 2 --start 0.125 --out results/bench3d/hex27

# The jointed rock mass at 64, 512 and 1,000 blocks, each with its contacts
# and bonded (docs/blocks.md): contact iterations per step, contact solve
# against the bonded solve, peak memory: results/bench_blocks/blocks.{md,json}.
# About 8 minutes.
bench-blocks: deps build
	$(PYTHON) scripts/blocks/bench.py

# CalculiX 2.20 on the same hex20 mesh and loads as subcontact (block on
# block, bonded and frictional contact, lc = 0.125, 1/12, 0.0625), ccx on 1 and
# 2 threads: results/bench_ccx/ccx.{md,csv}. Installs calculix-ccx (Debian) if
# missing; only this target needs it. About an hour on 2 cores: each run waits
# (up to 10 min) for an idle machine. Options: BENCH_CCX_ARGS="--lc 0.125".
bench-ccx: deps build
	@command -v ccx >/dev/null 2>&1 || { \
	  echo "ccx not found: installing it with apt-get (Debian package calculix-ccx)"; \
	  if command -v apt-get >/dev/null 2>&1; then \
	    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq calculix-ccx >/dev/null) || \
	    { echo "error: could not install calculix-ccx; run 'apt-get install -y calculix-ccx' as root"; exit 1; }; \
	  else echo "error: ccx is missing and apt-get is not available: install CalculiX 2.x so that 'ccx' is on PATH"; exit 1; fi; }
	@test -x /usr/bin/time || { echo "/usr/bin/time not found: installing the Debian package time"; \
	  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq time >/dev/null) || \
	  { echo "error: could not install /usr/bin/time; run 'apt-get install -y time' as root"; exit 1; }; }
	$(PYTHON) scripts/ccx/bench_ccx.py $(BENCH_CCX_ARGS)

# The numerical stress tests, long cases included: results/stress/stress.md.
# strace, whose fault injection kills runs at each system call of their
# commit (tests/transaction.rs; a few points in `make test`, every one in
# `make stress`).
deps-strace:
	@command -v strace >/dev/null 2>&1 || { \
	  echo "strace not found: installing it with apt-get (Debian package strace)"; \
	  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq strace >/dev/null) || \
	  { echo "error: could not install strace; run 'apt-get install -y strace' as root"; exit 1; }; }

# Every binary runs (--no-fail-fast) and the failures are listed at the
# end. The scenes whose rigid joints alone (rigid_fallback = false) issue
# 28 has not yet made converge are skipped here and run by `make
# stress-open`, which fails until they do (docs/corpus.md,
# docs/convergence.md say where each stands); `make stress` runs them as
# written, ending through the fallback to joints that deform. Rigid
# joints that end only through the augmented rounds at a cost beyond
# make stress's (blocks3d, 18 minutes) are here too.
STRESS_OPEN = blocks3d_unconfined_with_rigid_joints \
	blocks3d_unconfined_rigid_through_augmented_rounds \
	the_tunnel_meshed_coarser_away_from_the_opening_converges_without_cuts
stress: deps deps-strace
	$(CARGO) test --release --no-fail-fast --test stress --test transaction --test convergence \
	  --test joint_sets --test corpus --test initial_stage -- --ignored --nocapture $(addprefix --skip ,$(STRESS_OPEN))

stress-open: deps build
	$(CARGO) test --release --no-fail-fast --test convergence --test corpus -- --ignored --nocapture \
	  --exact $(STRESS_OPEN)

test: deps deps-strace
	$(CARGO) test --release

# The habits CI enforces: the tree formatted (rustfmt.toml) and clippy clean
# on every target, warnings as errors. rustdoc's warnings (links that do not
# resolve, unclosed tags) fail it too, over the private items as well; a
# link from a public item's doc to a private one is allowed, these docs
# being read with the private items.
lint:
	$(CARGO) fmt --check
	$(CARGO) clippy --release --all-targets -- -D warnings
	RUSTDOCFLAGS="-D warnings -A rustdoc::private_intra_doc_links" $(CARGO) doc --no-deps --document-private-items

# Fuzzing: the MSH reader, the scene parser and a whole `check` on mutated
# inputs, and the commit of result files under kills and foreign files, FUZZ_SECONDS per target (default 60: about 3 minutes); a panic or
# a hang fails and saves the input under target/tmp/fuzz-found/. A mutation
# loop on stable Rust (cargo-fuzz needs nightly); `make test` runs it 4 s.
FUZZ_SECONDS ?= 60
fuzz: deps
	FUZZ_SECONDS=$(FUZZ_SECONDS) $(CARGO) test --release --test fuzz -- --nocapture --test-threads 1

# MPI: OpenMPI with its headers and the clang the mpi crate's bindings need
# (Debian), then the MPI tests (tests/mpi.rs: 2 and 3 ranks on localhost
# against the serial run) with the binary built with the cargo feature mpi,
# in its own target directory so that `make test`'s build stays as it is.
# `mpicc` alone is not enough: Debian's ParaView brings openmpi-bin (mpirun,
# mpicc) without libopenmpi-dev, so the check compiles `#include <mpi.h>`.
MPI_TARGET := target/mpi

deps-mpi:
	@{ command -v mpirun >/dev/null 2>&1 && printf '#include <mpi.h>\n' | mpicc -E -x c - >/dev/null 2>&1 && ls /usr/lib/llvm-*/lib/libclang*.so* >/dev/null 2>&1; } || { \
	  echo "OpenMPI (mpirun, mpicc and the header mpi.h) or libclang not found: installing openmpi-bin libopenmpi-dev libclang-dev with apt-get"; \
	  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq openmpi-bin libopenmpi-dev libclang-dev >/dev/null) || \
	  { echo "error: could not install OpenMPI; run 'apt-get install -y openmpi-bin libopenmpi-dev libclang-dev' as root"; exit 1; }; }

test-mpi: deps deps-mpi
	CARGO_TARGET_DIR=$(MPI_TARGET) $(CARGO) test --release --features mpi --test mpi

# The dense and the iterative interface on the same 3D scenes (block on
# block on hex20/hex27/tet10, the 1.09e6-DOF strip): the table of
# docs/bench3d.md, results/bench3d/interfaces.md. About 20 minutes; the
# strip's dense run peaks at 21.5 GB.
bench-interface: deps build
	$(PYTHON) scripts/bench3d/interfaces.py

# The scaling runs of docs/scaling.md: a 5.7e5-DOF column on a column on 1 and
# 2 threads, 1 and 2 MPI ranks, 2, 4 and 8 substructures per body:
# results/scaling/scaling.{md,json}. About 15 minutes on 2 cores.
scaling: deps deps-mpi build
	CARGO_TARGET_DIR=$(MPI_TARGET) $(CARGO) build --release --features mpi
	$(PYTHON) scripts/scaling/scaling.py

clean:
	rm -rf results/*/ target
