/* memguard.h - estimate the memory a scene needs before allocating it, and refuse a scene that
 * cannot fit ("needs X GiB, Y GiB available") instead of being killed by the kernel mid-run. */
#ifndef MC_MEMGUARD_H
#define MC_MEMGUARD_H

#include "core/error.h"
#include "case/scene.h"

/* Estimated peak bytes of running scene s (surface fields, operator, contact solver with its
 * coarse levels, stress volumes and workspaces). A model calibrated against measured peaks
 * (reports/bench: memory): it errs on the high side by design. Per process: over MPI processes
 * (core/dist.h) the operators' spectra and transform buffers and the contact solvers' work
 * arrays count 1/P, every replicated array in full (the surface fields, the preconditioner's
 * buffers and the gradient and free set gathered for it, the kernel table, the stress layers). */
double mc_memory_estimate(const mc_scene *s);

/* The same for a run over `ranks` MPI processes (mc_memory_estimate: the run's own count), e.g.
 * to predict a cluster run from one process (bench mpi). */
double mc_memory_estimate_ranks(const mc_scene *s, int ranks);

/* Memory the system can still give, bytes (MemAvailable of /proc/meminfo; physical memory if
 * that is unreadable); MC_MEMORY_LIMIT in the environment (bytes, for tests) overrides it. */
double mc_memory_available(void);

/* MC_OK if the estimate fits into the available memory, else MC_ERR_NOMEM with a message naming
 * both in GiB and what to reduce. Over MPI processes rank 0's available memory decides for all
 * (collective). */
int mc_memory_check(const mc_scene *s, mc_error *err);

#endif
