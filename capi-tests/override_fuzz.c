/*
 * override_fuzz: shader overrides that are dnsr's own valid modules with 1-6 words changed, handed to
 * dnsr_context_create. None may take the process down: dnsr must refuse every module that the reflection library
 * or the driver cannot take (DNSR_ERROR_SHADER_INTERFACE with a message), and a module it accepts must create a
 * context without a validation message.
 *
 * Each batch of cases runs in a child process, which reports every case to the parent before and after it runs:
 * a child killed by a signal (an abort in a C library, a crash in the driver) or exiting early names the case
 * that killed it, and the next batch goes on after that case, so one run lists every such case.
 *
 * Besides the seeded random cases, a few targeted ones change exactly what once aborted the process inside
 * SPIRV-Reflect (an image's Sampled operand, an interface variable's storage class, a huge id bound) or the driver
 * (a descriptor set that SPIRV-Reflect does not report).
 *
 * Usage: override_fuzz [--seed S] [--cases N] [--batch N] [--first K]   (rerun case K: --seed S --cases 1 --first K);
 * the environment variable DNSR_SPV_DIR replaces the folder of dnsr's modules compiled in.
 */
#define _POSIX_C_SOURCE 200809L

#include "host.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef DNSR_SPV_DIR
#error "DNSR_SPV_DIR: the folder of dnsr's compiled variants (shaders/spv)"
#endif

/* The variants a default context (FP32, R32_SFLOAT output, hit-mask input) runs, and prepare, whose override is
 * checked though a hit-mask context creates no prepare pipeline. */
static const char *const VARIANTS[] = {"prepare", "tile_classification_r32f", "filter", "filter_later",
                                       "filter_later_final_r32f", "filter_final_r32f"};
#define VARIANT_COUNT (sizeof VARIANTS / sizeof VARIANTS[0])

typedef struct Module {
    uint32_t *words;
    size_t count;
} Module;

static Module modules[VARIANT_COUNT];

static Module load(const char *name)
{
    char path[512];
    const char *dir = getenv("DNSR_SPV_DIR") ? getenv("DNSR_SPV_DIR") : DNSR_SPV_DIR;
    snprintf(path, sizeof path, "%s/%s.spv", dir, name);
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL, "cannot open %s: %s", path, strerror(errno));
    fseek(f, 0, SEEK_END);
    long bytes = ftell(f);
    fseek(f, 0, SEEK_SET);
    CHECK(bytes > 20 && bytes % 4 == 0, "%s: %ld bytes", path, bytes);
    Module m = {malloc((size_t)bytes), (size_t)bytes / 4};
    CHECK(fread(m.words, 4, m.count, f) == m.count, "short read of %s", path);
    fclose(f);
    return m;
}

static uint64_t rng_state;
static uint32_t next(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state >> 11);
}

/* The word index of the first instruction with `opcode` at or after word `from`, or 0. */
static size_t find(const Module *m, uint32_t opcode, size_t from)
{
    for (size_t i = 5; i < m->count && (m->words[i] >> 16); i += m->words[i] >> 16)
        if (i >= from && (m->words[i] & 0xFFFF) == opcode) return i;
    return 0;
}

enum { OP_ENTRY_POINT = 15, OP_TYPE_IMAGE = 25, OP_VARIABLE = 59, OP_DECORATE = 71, DECORATION_DESCRIPTOR_SET = 34 };
#define TARGETED_CASES 5u

/* Case `index`: the module of a variant with what the case changes; returns the variant and writes a description. */
static uint32_t *make_case(uint64_t seed, uint32_t index, size_t *count, const char **variant, char *what, size_t cap)
{
    rng_state = seed * 0x9E3779B97F4A7C15ull + index * 0xBF58476D1CE4E5B9ull + 1;
    for (int i = 0; i < 4; i++) next();
    const Module *m = &modules[index < TARGETED_CASES ? 2 : next() % VARIANT_COUNT];
    *variant = VARIANTS[m - modules];
    uint32_t *w = malloc(m->count * 4);
    memcpy(w, m->words, m->count * 4);
    *count = m->count;
    size_t at;
    switch (index) {
    case 0: /* an image type's Sampled operand 3 (SPIRV-Reflect asserted "unknown image sampled value") */
        at = find(m, OP_TYPE_IMAGE, 0);
        CHECK(at, "%s has no OpTypeImage", *variant);
        w[at + 7] = 3;
        snprintf(what, cap, "OpTypeImage at word %zu: Sampled 3", at);
        return w;
    case 1: /* the id bound at 2^30 (SPIRV-Reflect allocated tables for it) */
        w[3] = 1u << 30;
        snprintf(what, cap, "id bound 2^30");
        return w;
    case 2: { /* the entry point's first interface variable in Workgroup storage ("Unsupported storage class") */
        size_t ep = find(m, OP_ENTRY_POINT, 0), words = ep ? w[ep] >> 16 : 0;
        CHECK(ep && words > 4, "%s: no entry point with an interface", *variant);
        uint32_t id = w[ep + words - 1];
        for (at = find(m, OP_VARIABLE, 0); at && w[at + 2] != id; at = find(m, OP_VARIABLE, at + 1)) {}
        CHECK(at, "%s: the interface variable %u is not declared", *variant, id);
        w[at + 3] = 4;
        snprintf(what, cap, "interface variable %u in Workgroup storage", id);
        return w;
    }
    case 3: /* an image type's Dim 7 (no such dimension) */
        at = find(m, OP_TYPE_IMAGE, 0);
        w[at + 3] = 7;
        snprintf(what, cap, "OpTypeImage at word %zu: Dim 7", at);
        return w;
    case 4: /* a DescriptorSet decoration of 0xFFFFFFFF (SPIRV-Reflect's "no set": the binding went unchecked, and
             * lavapipe crashed creating the pipeline) */
        for (at = find(m, OP_DECORATE, 0); at && w[at + 2] != DECORATION_DESCRIPTOR_SET; at = find(m, OP_DECORATE, at + 1)) {}
        CHECK(at, "%s has no DescriptorSet decoration", *variant);
        w[at + 3] = 0xFFFFFFFFu;
        snprintf(what, cap, "OpDecorate at word %zu: DescriptorSet 0xFFFFFFFF", at);
        return w;
    }
    uint32_t changes = 1 + next() % 6;
    int n = snprintf(what, cap, "%u word(s):", changes);
    for (uint32_t c = 0; c < changes; c++) {
        /* Mostly instructions; now and then the header's version, generator, bound or schema. */
        size_t i = next() % 16 == 0 ? 1 + next() % 4 : 5 + next() % (m->count - 5);
        uint32_t old = w[i], v;
        switch (next() % 6) {
        case 0: v = next() ^ (next() << 21); break;                        /* anything */
        case 1: v = old ^ (1u << (next() % 32)); break;                    /* one bit */
        case 2: v = next() % 64; break;                                    /* a small literal or enum */
        case 3: v = old + (next() % 2 ? 1u : 0xFFFFFFFFu); break;          /* one off: another id */
        case 4: v = 1 + next() % (m->words[3] ? m->words[3] : 1); break;   /* any id of the module */
        default: v = (old & 0xFFFF0000u) | (next() % 400); break;          /* another opcode, same length */
        }
        w[i] = v;
        if (n > 0 && (size_t)n < cap) n += snprintf(what + n, cap - (size_t)n, " [%zu] %08x->%08x", i, old, v);
    }
    return w;
}

typedef struct Report {
    uint32_t index;
    int32_t done; /* 0: starting, 1: finished with `result` */
    int32_t result;
} Report;

static void send(int fd, Report r)
{
    CHECK(write(fd, &r, sizeof r) == (ssize_t)sizeof r, "pipe write: %s", strerror(errno));
}

/* The child: cases [first, end) through one host, each reported before and after. */
static void run_batch(int fd, uint64_t seed, uint32_t first, uint32_t end)
{
    Host host;
    host_create(&host);
    for (uint32_t i = first; i < end; i++) {
        send(fd, (Report){i, 0, 0});
        size_t count;
        const char *variant;
        char what[512];
        uint32_t *code = make_case(seed, i, &count, &variant, what, sizeof what);
        DnsrShaderOverride o = {variant, code, count * 4};
        DnsrContextCreateInfo info = host_create_info(&host, 64, 32);
        info.shaderOverrideCount = 1;
        info.pShaderOverrides = &o;
        DnsrContext context = NULL;
        DnsrResult r = dnsr_context_create(&info, &context);
        const char *message = dnsr_last_error_message();
        CHECK(r == DNSR_SUCCESS ? message[0] == 0 && context : r < 0 && message[0] && !context,
              "case %u (%s, %s): result %d, message \"%s\"", i, variant, what, r, message);
        /* A module that passes every check may still be one the driver cannot compile (Mesa's SPIR-V reader lags
         * behind the validator's rules): a refusal, reported through dnsr, and the driver's own messages with it. */
        bool driver_refused = r == DNSR_ERROR_VULKAN && strstr(message, "vkCreateComputePipelines");
        CHECK(r == DNSR_SUCCESS || r == DNSR_ERROR_SHADER_INTERFACE || driver_refused, "case %u (%s, %s): result %d, \"%s\"",
              i, variant, what, r, message);
        if (driver_refused) {
            fprintf(stderr, "override_fuzz: case %u (%s, %s): the driver refused it (above)\n", i, variant, what);
            host.validationMessages = 0;
        }
        dnsr_context_destroy(context);
        host_expect_clean(&host, what);
        free(code);
        send(fd, (Report){i, 1, r});
    }
    host_destroy(&host);
}

int main(int argc, char **argv)
{
    uint64_t seed = 0x0dd5eedu;
    /* CMakeLists.txt reads the default `cases` below and runs it as two tests of half each. */
    uint32_t cases = 2000, batch = 250, first = 0;
    for (int i = 1; i + 1 < argc; i += 2) {
        uint64_t v = strtoull(argv[i + 1], NULL, 0);
        if (!strcmp(argv[i], "--seed")) seed = v;
        else if (!strcmp(argv[i], "--cases")) cases = (uint32_t)v;
        else if (!strcmp(argv[i], "--batch")) batch = (uint32_t)v;
        else if (!strcmp(argv[i], "--first")) first = (uint32_t)v;
        else host_fail(__FILE__, __LINE__, "arguments", "unknown option %s", argv[i]);
    }
    for (size_t v = 0; v < VARIANT_COUNT; v++) modules[v] = load(VARIANTS[v]);

    uint32_t accepted = 0, refused = 0, driver = 0, killed = 0, end = first + cases;
    for (uint32_t start = first; start < end;) {
        int fds[2];
        CHECK(pipe(fds) == 0, "pipe: %s", strerror(errno));
        fflush(stdout), fflush(stderr);
        pid_t pid = fork();
        CHECK(pid >= 0, "fork: %s", strerror(errno));
        if (pid == 0) {
            close(fds[0]);
            run_batch(fds[1], seed, start, start + batch < end ? start + batch : end);
            close(fds[1]);
            exit(0); /* with the leak check */
        }
        close(fds[1]);
        Report r, last = {start, 1, 0};
        uint32_t started = start;
        bool running = false;
        while (read(fds[0], &r, sizeof r) == (ssize_t)sizeof r) {
            last = r;
            running = !r.done;
            if (running) started = r.index;
            else if (r.result == DNSR_SUCCESS) accepted++;
            else if (r.result == DNSR_ERROR_VULKAN) driver++;
            else refused++;
        }
        close(fds[0]);
        int status = 0;
        CHECK(waitpid(pid, &status, 0) == pid, "waitpid: %s", strerror(errno));
        bool clean = WIFEXITED(status) && WEXITSTATUS(status) == 0;
        if (!clean) {
            killed++;
            size_t count;
            const char *variant;
            char what[512];
            free(make_case(seed, started, &count, &variant, what, sizeof what));
            fprintf(stderr, "override_fuzz: case %u (seed %#llx, %s, %s) %s %d%s\n", started,
                    (unsigned long long)seed, variant, what, WIFSIGNALED(status) ? "killed the process: signal" : "failed: exit",
                    WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status), running ? "" : " (after the case)");
        }
        start = (running || !clean) ? started + 1 : last.index + 1;
        if (clean && !running) start = start > end ? end : start;
    }
    printf("override_fuzz: %u cases (seed %#llx): %u accepted, %u refused by dnsr, %u refused by the driver, %u killed or "
           "failed the process\n", cases, (unsigned long long)seed, accepted, refused, driver, killed);
    return killed ? 1 : 0;
}
