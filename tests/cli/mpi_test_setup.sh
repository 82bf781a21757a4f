# Sourced by the mpirun tests (mpi_deform_test.sh, mpi_split_test.sh) with their arguments
# FFDKIT_CLI MPIEXEC WIDGET_FILE: sets cli, mpiexec, tool and a work folder removed on exit,
# and lets Open MPI run as root (it refuses unless told) on fewer cores than ranks.
cli="$1"
mpiexec="$2"
tool="$3"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
