/* test_cli_pipe.c - the CLI and its standard output (apps/softrast/main.c):
 * text written into a pipe whose reader has gone, or onto a full device,
 * must end the process with a non-zero exit status - never death by
 * SIGPIPE - and at most one line on stderr.  The child starts with SIGPIPE
 * at its default action, as a shell would start it, so the test fails if
 * the CLI stops ignoring it. */
#include "sr_test.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct run_result {
    bool exited;          /* normally, not by a signal */
    int status;           /* exit status, or the signal */
    char err[4096];       /* its stderr */
    char out[65536];      /* its stdout, when captured */
    size_t out_len;
} run_result;

typedef enum out_kind { OUT_CLOSED_PIPE, OUT_DEV_FULL, OUT_CAPTURE } out_kind;

static size_t read_fd(int fd, char *buf, size_t cap)
{
    size_t n = 0;
    for (;;) {
        ssize_t got = read(fd, buf + n, cap - 1 - n);
        if (got < 0 && errno == EINTR) {
            continue;
        }
        if (got <= 0 || (n += (size_t)got) == cap - 1) {
            break;
        }
    }
    buf[n] = 0;
    return n;
}

static bool run(const char *const *args, out_kind kind, run_result *r)
{
#ifndef SR_CLI_PATH
    (void)args, (void)kind, (void)r;
    return false;
#else
    memset(r, 0, sizeof *r);
    int out[2], err[2];
    if (pipe(out) != 0 || pipe(err) != 0) {
        return false;
    }
    if (kind == OUT_CLOSED_PIPE) {
        close(out[0]); /* no reader: every write to out[1] is EPIPE/SIGPIPE */
        out[0] = -1;
    }
    pid_t pid = fork();
    if (pid < 0) {
        return false;
    }
    if (pid == 0) {
        signal(SIGPIPE, SIG_DFL);
        int fd = kind == OUT_DEV_FULL ? open("/dev/full", O_WRONLY) : out[1];
        dup2(fd, STDOUT_FILENO);
        dup2(err[1], STDERR_FILENO);
        const char *argv[48];
        if (sr_test_program_argv(SR_CLI_PATH, args, argv, sizeof argv / sizeof argv[0])) {
            execv(argv[0], (char *const *)argv);
        }
        _exit(127);
    }
    close(out[1]);
    close(err[1]);
    if (kind == OUT_CAPTURE) {
        r->out_len = read_fd(out[0], r->out, sizeof r->out);
    }
    if (out[0] >= 0) {
        close(out[0]);
    }
    read_fd(err[0], r->err, sizeof r->err);
    close(err[0]);
    int st;
    while (waitpid(pid, &st, 0) < 0) {
        if (errno != EINTR) {
            return false;
        }
    }
    r->exited = WIFEXITED(st);
    r->status = r->exited ? WEXITSTATUS(st) : WTERMSIG(st);
    return true;
#endif
}

static int count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++) {
        n += *s == '\n';
    }
    return n;
}

static const char *const *const text_commands[] = {
    (const char *const[]){ "--help", NULL },
    (const char *const[]){ "--version", NULL },
    (const char *const[]){ "render", "--help", NULL },
    (const char *const[]){ "svg", "--help", NULL },
    (const char *const[]){ "demo", "--help", NULL },
};
#define N_TEXT_COMMANDS (int)(sizeof text_commands / sizeof text_commands[0])

SR_TEST(text_into_a_closed_pipe_exits_non_zero_quietly_not_by_sigpipe)
{
    for (int i = 0; i < N_TEXT_COMMANDS; i++) {
        run_result r;
        if (!run(text_commands[i], OUT_CLOSED_PIPE, &r)) {
            SKIP("the CLI was not built");
        }
        if (!r.exited) {
            sr_test_fail(__FILE__, __LINE__, "softrast %s %s: killed by signal %d",
                         text_commands[i][0], text_commands[i][1] ? text_commands[i][1] : "",
                         r.status);
            continue;
        }
        CHECK_EQ(r.status, 1);
        CHECK_EQ(count_lines(r.err), 0); /* the reader left on purpose: nothing to say */
    }
}

SR_TEST(text_onto_a_full_device_gives_one_line_and_status_1)
{
    for (int i = 0; i < N_TEXT_COMMANDS; i++) {
        run_result r;
        if (!run(text_commands[i], OUT_DEV_FULL, &r)) {
            SKIP("the CLI was not built");
        }
        if (access("/dev/full", W_OK) != 0) {
            SKIP("no /dev/full");
        }
        CHECK(r.exited);
        CHECK_EQ(r.status, 1);
        CHECK_EQ(count_lines(r.err), 1);
        CHECK_STR_CONTAINS(r.err, "softrast: cannot write to standard output: ");
        CHECK_STR_CONTAINS(r.err, strerror(ENOSPC));
    }
}

SR_TEST(text_into_an_open_pipe_arrives_whole_with_status_0)
{
    for (int i = 0; i < N_TEXT_COMMANDS; i++) {
        run_result r;
        if (!run(text_commands[i], OUT_CAPTURE, &r)) {
            SKIP("the CLI was not built");
        }
        CHECK(r.exited);
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err[0], 0);
        CHECK(r.out_len > 0 && r.out[r.out_len - 1] == '\n');
    }
    /* The longest text (render --help) is more than one pipe-sized stdio
     * buffer: it still arrives whole. */
    run_result r;
    REQUIRE(run(text_commands[2], OUT_CAPTURE, &r));
    CHECK(r.out_len > 4096);
    CHECK_STR_CONTAINS(r.out, "usage:");
}

SR_TEST(a_failing_command_keeps_its_status_when_stdout_is_closed)
{
    run_result r;
    if (!run((const char *const[]){ "no-such-command", NULL }, OUT_CLOSED_PIPE, &r)) {
        SKIP("the CLI was not built");
    }
    CHECK(r.exited);
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
}
