/* A test's stand-in for a user's Ctrl-C at the worst moment (bad_input_test
 * `CtrlCJustAfterTheOutputsArePutInPlaceEndsTheRunAsItWould`): preloaded into `shoal`, it
 * passes every rename(2) through and, once the file named by SHOAL_TEST_INTERRUPT_AFTER_RENAME
 * has been put in place, sends the process SIGINT, as the terminal would. Nothing in shoal
 * knows of it. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int rename(const char* from, const char* to) {
    static int (*real)(const char*, const char*) = NULL;
    if (!real) real = (int (*)(const char*, const char*))dlsym(RTLD_NEXT, "rename");
    const int rc = real(from, to);
    const char* after = getenv("SHOAL_TEST_INTERRUPT_AFTER_RENAME");
    if (rc == 0 && after && strcmp(to, after) == 0) kill(getpid(), SIGINT);
    return rc;
}
