/* dist.c - the run's communicator (dist.h). */
#include "core/dist.h"

static double comm_seconds;

double mc_dist_comm_seconds(void) { return comm_seconds; }
void mc_dist_comm_add(double s) { comm_seconds += s; }

#ifdef MC_MPI
double mc_dist_clock(void) { return MPI_Wtime(); }

static MPI_Comm run_comm = MPI_COMM_NULL;

void mc_dist_set(MPI_Comm comm) { run_comm = comm; }
MPI_Comm mc_dist_comm(void) { return run_comm; }
int mc_dist_active(void) { return run_comm != MPI_COMM_NULL; }

int mc_dist_size(void)
{
    int p = 1;
    if (run_comm != MPI_COMM_NULL)
        MPI_Comm_size(run_comm, &p);
    return p;
}

int mc_dist_rank(void)
{
    int r = 0;
    if (run_comm != MPI_COMM_NULL)
        MPI_Comm_rank(run_comm, &r);
    return r;
}

int mc_dist_root_int(int v)
{
    if (run_comm != MPI_COMM_NULL)
        MPI_Bcast(&v, 1, MPI_INT, 0, run_comm);
    return v;
}

int mc_dist_max_int(int v)
{
    if (run_comm != MPI_COMM_NULL)
        MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_MAX, run_comm);
    return v;
}

void mc_dist_bcast(double *v, size_t n, int root)
{
    if (run_comm == MPI_COMM_NULL)
        return;
    const double t0 = MPI_Wtime();
    const size_t chunk = (size_t)1 << 30; /* MPI counts are int */
    for (size_t at = 0; at < n; at += chunk)
        MPI_Bcast(v + at, (int)(n - at < chunk ? n - at : chunk), MPI_DOUBLE, root, run_comm);
    comm_seconds += MPI_Wtime() - t0;
}

void mc_dist_max(double *v, int n)
{
    if (run_comm != MPI_COMM_NULL && n > 0)
        MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MAX, run_comm);
}
#else
double mc_dist_clock(void) { return 0; }
int mc_dist_active(void) { return 0; }
int mc_dist_size(void) { return 1; }
int mc_dist_rank(void) { return 0; }
int mc_dist_root_int(int v) { return v; }
int mc_dist_max_int(int v) { return v; }
void mc_dist_bcast(double *v, size_t n, int root)
{
    (void)v;
    (void)n;
    (void)root;
}
void mc_dist_max(double *v, int n)
{
    (void)v;
    (void)n;
}
#endif
