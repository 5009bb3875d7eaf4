/* memguard.h - estimate the memory a scene needs before allocating it, and refuse a scene that
 * cannot fit ("needs X GiB, Y GiB available") instead of being killed by the kernel mid-run. */
#ifndef MC_MEMGUARD_H
#define MC_MEMGUARD_H

#include "core/error.h"
#include "case/scene.h"
#include "plastic/eigen_op.h"

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

/* The elastic-plastic stage of scene s on grid g once its volume v is chosen (the pre-run
 * estimate above cannot know it: the depth and the columns follow from the elastic contact):
 * the bytes the stage adds to mc_memory_estimate at its peak, inside the loop's sweeps: the
 * operators (the Love stresses at the cuboid centres, mc_eigen_stress_estimate,
 * mc_eigen_disp_estimate) and the loop's arrays (mc_plastic_loop_bytes, the yielding cells
 * counted as a tenth of the volume), with its output fields once the loop has freed them;
 * shortcut (nothing yields): the output fields alone. */
double mc_memory_estimate_plastic(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v,
                                  int shortcut);

/* MC_OK if mc_memory_estimate(s) + mc_memory_estimate_plastic(...) fits into the available
 * memory, else MC_ERR_NOMEM naming both and the volume. */
int mc_memory_check_plastic(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v,
                            int shortcut, mc_error *err);

/* The running-in of scene s (pipeline/runin.h) on grid g with plastic volume v: the bytes it adds
 * to mc_memory_estimate at its peak, inside a run-down step's loop: the elastic-plastic stage's
 * estimate (its state and the yield check's arrays are lent to the loop) and its surface
 * arrays. The operators are counted although a running-in builds them only at its first
 * yielding step. */
double mc_memory_estimate_runin(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v);

/* MC_OK if mc_memory_estimate(s) + mc_memory_estimate_runin(...) fits into the available
 * memory, else MC_ERR_NOMEM naming the running-in, both figures and the volume. */
int mc_memory_check_runin(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v,
                          mc_error *err);

#endif
