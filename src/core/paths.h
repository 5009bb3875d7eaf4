/* paths.h - the one limit on file path lengths that scenes, readers and outputs share. */
#ifndef MC_PATHS_H
#define MC_PATHS_H

#define MC_PATH_MAX 1024 /* bytes, including the terminating NUL */

#endif
