# Sourced by the mpirun tests (mpi_deform_test.sh, mpi_split_test.sh) with their arguments
# FFDKIT_CLI MPIEXEC WIDGET_FILE: sets cli, mpiexec, tool and a work folder removed on exit,
# and lets Open MPI run as root (it refuses unless told) on fewer cores than ranks.
cli="$1"
mpiexec="$2"
tool="$3"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Start-up and shutdown without waits the tests do not need (what the ranks compute and write is
# the same): the ranks of one machine talk through Open MPI's own shared-memory layer (ob1), as
# UCX's start-up doubled each mpirun (0.4 s against 0.2 s); and a batch whose ranks exit with an
# error ends when they have, not a second later (mpirun waits that long before it kills what is left:
# odls_base_sigkill_timeout, 1 s by default; 1.5 s against 0.4 s for each refused batch).
export OMPI_MCA_pml="${OMPI_MCA_pml:-ob1}" OMPI_MCA_odls_base_sigkill_timeout="${OMPI_MCA_odls_base_sigkill_timeout:-0}"
