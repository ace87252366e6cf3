/* cli_plot.c - the plotting scripts' runner: Python on a script, its output
 * written completely or not at all, and the plot of one input file shared by
 * the subcommands (path, sweep, homogenize). */
#define _POSIX_C_SOURCE 200809L /* fork, waitpid, sigprocmask */
#include "cli/cli.h"

#include <errno.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef RN_PYTHON3
#define RN_PYTHON3 "python3"
#endif

int rn_cli_run_script(const char *script_env, const char *default_script,
                      const char *const *args) {
  const char *script = getenv(script_env), *python = getenv("RODNET_PYTHON");
  const char *argv[11];
  int n = 0;
  if (!script || !*script) script = default_script;
  if (!python || !*python) python = RN_PYTHON3;
  argv[n++] = python;
  argv[n++] = script;
  for (int i = 0; args[i] && n < 10; i++) argv[n++] = args[i];
  argv[n] = NULL;
  fflush(stdout);
  fflush(stderr);
  /* no signal between the fork and the child's registration: the handler
   * kills the script (cli_signals.c) */
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  sigaddset(&block, SIGHUP);
  sigprocmask(SIG_BLOCK, &block, &old);
  pid_t pid = fork();
  if (pid == 0) {
    sigprocmask(SIG_SETMASK, &old, NULL);
    execvp(python, (char *const *)(uintptr_t)argv);
    _exit(127);
  }
  if (pid > 0) rn_cli_child((long)pid);
  sigprocmask(SIG_SETMASK, &old, NULL);
  if (pid < 0) return -1;
  int status = 0, rc = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) {
      rc = -1;
      break;
    }
  rn_cli_child(0);
  return !rc && WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}

int rn_cli_run_script_to(const char *script_env, const char *default_script,
                         const char *const *args, const char *output) {
  struct stat sb;
  /* a device (/dev/null) or FIFO is written in place, as atomic_file.h does */
  if (stat(output, &sb) == 0 && !S_ISREG(sb.st_mode) && !S_ISDIR(sb.st_mode))
    return rn_cli_run_script(script_env, default_script, args);
  const char *slash = strrchr(output, '/'), *dot = strrchr(output, '.');
  const char *ext = dot && (!slash || dot > slash + 1) ? dot : "";
  size_t len = strlen(output) + strlen(ext) + 48;
  char *tmp = malloc(len);
  const char *targs[9];
  int n = 0, rc;
  if (!tmp) return -1;
  snprintf(tmp, len, "%s.tmp.%ld%s", output, (long)getpid(), ext);
  for (; args[n] && n < 8; n++) targs[n] = args[n] == output ? tmp : args[n];
  targs[n] = NULL;
  rn_cli_temp_file(tmp, 1);
  rc = rn_cli_run_script(script_env, default_script, targs);
  if (rc == 0 && rename(tmp, output) != 0) rc = -1;
  if (rc) remove(tmp);
  rn_cli_temp_file(tmp, 0);
  free(tmp);
  return rc;
}

int rn_cli_plot(const char *script_env, const char *default_script, const char *input,
                const char *png) {
  const char *const args[] = {input, png, NULL};
  return rn_cli_run_script_to(script_env, default_script, args, png);
}
