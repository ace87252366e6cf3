/* context.c - rn_context (last error), status names and messages, version. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/network_internal.h"
#include "rodnet.h"

enum { RN_MESSAGE_CAPACITY = 1024 };

struct rn_context {
  rn_status last;
  char message[RN_MESSAGE_CAPACITY];
};

const char *rn_status_name(rn_status s) {
  switch (s) {
#define RN_STATUS_NAME_(name, code, msg) \
  case name:                             \
    return #name;
    RN_STATUS_LIST(RN_STATUS_NAME_)
#undef RN_STATUS_NAME_
  }
  return "RN_UNKNOWN_STATUS";
}

const char *rn_status_message(rn_status s) {
  switch (s) {
#define RN_STATUS_MSG_(name, code, msg) \
  case name:                            \
    return msg;
    RN_STATUS_LIST(RN_STATUS_MSG_)
#undef RN_STATUS_MSG_
  }
  return "unknown status";
}

const char *rn_version_string(void) { return RODNET_VERSION_STRING; }

void rn_version(int *major, int *minor, int *patch) {
  if (major) *major = RODNET_VERSION_MAJOR;
  if (minor) *minor = RODNET_VERSION_MINOR;
  if (patch) *patch = RODNET_VERSION_PATCH;
}

rn_status rn_context_create(rn_context **ctx) {
  if (!ctx) return RN_ERR_ARG;
  *ctx = calloc(1, sizeof(**ctx));
  return *ctx ? RN_OK : RN_ERR_ALLOC;
}

void rn_context_destroy(rn_context **ctx) {
  if (!ctx || !*ctx) return;
  free(*ctx);
  *ctx = NULL;
}

const char *rn_context_last_error(const rn_context *ctx) {
  return ctx ? ctx->message : "";
}

#if defined(__GNUC__)
__attribute__((format(printf, 4, 0)))
#endif
static void
context_vset(rn_context *ctx, rn_status s, const char *where, const char *fmt,
             va_list ap) {
  int used = 0;
  ctx->last = s;
  if (where) {
    used = snprintf(ctx->message, sizeof(ctx->message), "%s: ", where);
    if (used < 0 || (size_t)used >= sizeof(ctx->message)) used = 0;
  }
  if (fmt) {
    vsnprintf(ctx->message + used, sizeof(ctx->message) - (size_t)used, fmt, ap);
  } else {
    ctx->message[used] = '\0';
  }
}

rn_status rn_context_set_error(rn_context *ctx, rn_status s, const char *fmt, ...) {
  va_list ap;
  if (!ctx) return s;
  va_start(ap, fmt);
  context_vset(ctx, s, NULL, fmt, ap);
  va_end(ap);
  return s;
}

void rn_context_clear_error(rn_context *ctx) {
  if (!ctx) return;
  ctx->last = RN_OK;
  ctx->message[0] = '\0';
}

rn_status rn_fail(rn_context *ctx, rn_status s, const char *where, const char *fmt, ...) {
  va_list ap;
  if (!ctx) return s;
  va_start(ap, fmt);
  context_vset(ctx, s, where, fmt, ap);
  va_end(ap);
  return s;
}
