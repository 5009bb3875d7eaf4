/* cli.h - the commands of the microcontact executable (each returns the process exit status). */
#ifndef MC_CLI_H
#define MC_CLI_H

int mc_cli_run(int argc, char **argv);
int mc_cli_verify(int argc, char **argv);
int mc_cli_bench(int argc, char **argv);

#endif
