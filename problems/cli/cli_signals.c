/* cli_signals.c - a signal that ends the command (SIGINT, SIGTERM, SIGHUP)
 * leaves no temporary file behind: the handler kills the running plotting
 * script, removes every temporary file being written (atomic_file.h announces
 * them through its hook; the scripts' temporary outputs are registered by
 * rn_cli_run_script_to), then lets the signal take its default action, so the
 * exit status still reports it.  Only async-signal-safe calls in the handler
 * (kill, waitpid, unlink, raise). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <signal.h>
#include <stddef.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "cli/cli.h"

enum { MAX_TEMPS = 32 };

/* The temporary files being written (their names stay valid while
 * registered) and the plotting script running (0: none). */
static const char *volatile temps[MAX_TEMPS];
static volatile sig_atomic_t child_pid = 0;

static const int signals[] = {SIGINT, SIGTERM, SIGHUP};
enum { NSIGNALS = (int)(sizeof signals / sizeof signals[0]) };

static void on_signal(int sig) {
  int saved = errno;
  pid_t c = (pid_t)child_pid;
  if (c > 0) {
    kill(c, SIGKILL); /* it may be writing into a temporary file */
    while (waitpid(c, NULL, 0) < 0 && errno == EINTR) {
    }
  }
  for (int i = 0; i < MAX_TEMPS; i++) {
    const char *t = temps[i];
    if (t) unlink(t);
  }
  /* SA_RESETHAND restored the default action: delivered on return */
  raise(sig);
  errno = saved;
}

void rn_cli_temp_file(const char *tmp, int active) {
  if (active) {
    for (int i = 0; i < MAX_TEMPS; i++)
      if (!temps[i]) {
        temps[i] = tmp;
        return;
      }
    return; /* more than MAX_TEMPS at once: not removed on a signal */
  }
  for (int i = 0; i < MAX_TEMPS; i++)
    if (temps[i] == tmp) temps[i] = NULL;
}

void rn_cli_child(long pid) { child_pid = (sig_atomic_t)pid; }

void rn_cli_signals_install(void) {
  struct sigaction sa, old;
  sigemptyset(&sa.sa_mask);
  for (int i = 0; i < NSIGNALS; i++) sigaddset(&sa.sa_mask, signals[i]);
  sa.sa_handler = on_signal;
  sa.sa_flags = SA_RESETHAND;
  for (int i = 0; i < NSIGNALS; i++) {
    /* a signal ignored by the caller (nohup) stays ignored */
    if (sigaction(signals[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(signals[i], &sa, NULL);
  }
  rn_file_set_temp_hook(rn_cli_temp_file);
}
