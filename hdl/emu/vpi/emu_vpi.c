/*
 * emu_vpi.c: the encoder emulators (libcosim, cosim/src/ffi.rs) as Icarus
 * VPI system functions, so that hdl/emu/<device>_emu.v has one port list and
 * one body in Icarus and in Verilator (where the same calls go through DPI-C).
 *
 *   $emu_open(kind, path, f_emu_hz, transcript)  -> handle (int, < 0 on error)
 *   $emu_step(handle, pins)                      -> pins out (int)
 *   $emu_set_position(handle, device, position)  -> 0 / -1
 *   $emu_set_status(handle, device, name, value) -> 0 / -1
 *   $emu_schedule_fault(handle, toml)            -> 0 / -1
 *   $emu_set_motion(handle, device, toml)        -> 0 / -1
 *   $emu_count(handle, half)                     -> 32 bits: half 0 low, 1 high
 *   $emu_last_value(handle, device, half)        -> 32 bits: half 0 low, 1 high
 *   $emu_last_status(handle, device, name)       -> 0 / 1 / -1
 *   $emu_write_transcript(handle, path)          -> 0 / -1
 *   $emu_violations(handle)                      -> protocol violations so far
 *   $emu_print_violations(handle, instance)      -> prints those not yet shown, returns how many
 *
 * Every function returns 32 bits (iverilog types an unknown system function
 * as a 32-bit int at compile time; 64-bit values come as two halves, so no
 * .sft file is needed). Every failure prints the library's message (file, field and fix) with the
 * simulation time; the wrapper then stops the run. Transcripts named at
 * $emu_open are written at the end of the simulation.
 *
 * Build: gcc -shared -fPIC $(iverilog-vpi --cflags) emu_vpi.c -o emu.vpi \
 *          -L<target>/release -lcosim -Wl,-rpath,<target>/release
 * Run:   vvp -M <dir of emu.vpi> -m emu tb.vvp
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vpi_user.h>

/* The library's C ABI (cosim/src/ffi.rs). */
extern int32_t emu_open(const char *kind, const char *path, int64_t f_emu_hz);
extern int32_t emu_step(int32_t handle, int32_t pins);
extern int32_t emu_set_position(int32_t handle, int32_t device, int64_t position);
extern int32_t emu_set_status(int32_t handle, int32_t device, const char *name, int32_t value);
extern int32_t emu_schedule_fault(int32_t handle, const char *toml);
extern int32_t emu_set_motion(int32_t handle, int32_t device, const char *toml);
extern int64_t emu_count(int32_t handle);
extern int64_t emu_last_value(int32_t handle, int32_t device);
extern int32_t emu_last_status(int32_t handle, int32_t device, const char *name);
extern int32_t emu_write_transcript(int32_t handle, const char *path);
extern const char *emu_last_error(void);
extern int64_t emu_violations(int32_t handle);
extern const char *emu_take_violation(int32_t handle);

#define MAX_ARGS 5
#define MAX_TRANSCRIPTS 64

static struct {
    int32_t handle;
    char *path;
} transcripts[MAX_TRANSCRIPTS];
static int n_transcripts;

/* The arguments of the current call, as handles. */
static int args(vpiHandle out[MAX_ARGS]) {
    vpiHandle call = vpi_handle(vpiSysTfCall, NULL);
    vpiHandle it = vpi_iterate(vpiArgument, call);
    int n = 0;
    vpiHandle a;
    while (it && (a = vpi_scan(it)) != NULL) {
        if (n < MAX_ARGS)
            out[n] = a;
        n++;
    }
    return n;
}

static int64_t arg_int(vpiHandle h) {
    s_vpi_value v;
    v.format = vpiVectorVal;
    vpi_get_value(h, &v);
    int size = vpi_get(vpiSize, h);
    uint64_t lo = (uint32_t)v.value.vector[0].aval;
    uint64_t hi = size > 32 ? (uint32_t)v.value.vector[1].aval : 0;
    if (size == 32 && vpi_get(vpiSigned, h) && (lo & 0x80000000u))
        return (int64_t)(int32_t)lo;
    return (int64_t)((hi << 32) | lo);
}

/* A string argument: a literal, a parameter or a reg holding characters.
 * The library trims the leading NULs and spaces a wide reg carries. */
static char *arg_str(vpiHandle h) {
    s_vpi_value v;
    v.format = vpiStringVal;
    vpi_get_value(h, &v);
    return strdup(v.value.str ? v.value.str : "");
}

static void put_int(int32_t value) {
    vpiHandle call = vpi_handle(vpiSysTfCall, NULL);
    s_vpi_value v;
    v.format = vpiIntVal;
    v.value.integer = value;
    vpi_put_value(call, &v, NULL, vpiNoDelay);
}

/* One half of a 64-bit value (half 0: bits 31..0, half 1: bits 63..32). */
static void put_half(int64_t value, int64_t half) {
    uint64_t u = (uint64_t)value;
    put_int((int32_t)(uint32_t)(half ? u >> 32 : u & 0xffffffffu));
}

static void report(const char *what) {
    s_vpi_time t;
    t.type = vpiSimTime;
    vpi_get_time(NULL, &t);
    uint64_t now = ((uint64_t)(uint32_t)t.high << 32) | (uint32_t)t.low;
    vpi_printf("ERROR: %s at simulation time %llu: %s\n", what, (unsigned long long)now, emu_last_error());
}

static int32_t check(int32_t r, const char *what) {
    if (r < 0)
        report(what);
    return r;
}

static int wrong_count(int n, int want, const char *name) {
    if (n != want) {
        vpi_printf("ERROR: %s takes %d arguments, not %d\n", name, want, n);
        vpi_control(vpiFinish, 1);
        return 1;
    }
    return 0;
}

static PLI_INT32 open_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 4, "$emu_open"))
        return 0;
    char *kind = arg_str(a[0]), *path = arg_str(a[1]), *transcript = arg_str(a[3]);
    int32_t h = check(emu_open(kind, path, arg_int(a[2])), "$emu_open");
    /* A transcript path, trimmed of the spaces a wide reg may carry. */
    char *p = transcript;
    while (*p == ' ')
        p++;
    if (h > 0 && *p && n_transcripts < MAX_TRANSCRIPTS) {
        transcripts[n_transcripts].handle = h;
        transcripts[n_transcripts].path = strdup(p);
        n_transcripts++;
    }
    free(kind);
    free(path);
    free(transcript);
    put_int(h);
    return 0;
}

/* $emu_step runs on every emulator cycle: its two argument handles are
 * looked up at the first call of each call site and kept there (userdata),
 * and both arguments and the result pass as 32-bit integers. Iterating the
 * arguments anew at each call was about a tenth of an Icarus closed loop. */
struct step_site {
    vpiHandle handle;
    vpiHandle pins;
};

static int32_t int_arg(vpiHandle h) {
    s_vpi_value v;
    v.format = vpiIntVal;
    vpi_get_value(h, &v);
    return v.value.integer;
}

static PLI_INT32 step_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle call = vpi_handle(vpiSysTfCall, NULL);
    struct step_site *site = (struct step_site *)vpi_get_userdata(call);
    if (site == NULL) {
        vpiHandle a[MAX_ARGS];
        if (wrong_count(args(a), 2, "$emu_step"))
            return 0;
        site = (struct step_site *)malloc(sizeof *site);
        if (site == NULL) {
            vpi_printf("ERROR: $emu_step: out of memory\n");
            vpi_control(vpiFinish, 1);
            return 0;
        }
        site->handle = a[0];
        site->pins = a[1];
        vpi_put_userdata(call, site);
    }
    s_vpi_value v;
    v.format = vpiIntVal;
    v.value.integer = check(emu_step(int_arg(site->handle), int_arg(site->pins)), "$emu_step");
    vpi_put_value(call, &v, NULL, vpiNoDelay);
    return 0;
}

static PLI_INT32 set_position_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 3, "$emu_set_position"))
        return 0;
    put_int(check(emu_set_position((int32_t)arg_int(a[0]), (int32_t)arg_int(a[1]), arg_int(a[2])), "$emu_set_position"));
    return 0;
}

static PLI_INT32 set_status_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 4, "$emu_set_status"))
        return 0;
    char *name = arg_str(a[2]);
    put_int(check(emu_set_status((int32_t)arg_int(a[0]), (int32_t)arg_int(a[1]), name, (int32_t)arg_int(a[3])), "$emu_set_status"));
    free(name);
    return 0;
}

static PLI_INT32 schedule_fault_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 2, "$emu_schedule_fault"))
        return 0;
    char *toml = arg_str(a[1]);
    put_int(check(emu_schedule_fault((int32_t)arg_int(a[0]), toml), "$emu_schedule_fault"));
    free(toml);
    return 0;
}

static PLI_INT32 set_motion_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 3, "$emu_set_motion"))
        return 0;
    char *toml = arg_str(a[2]);
    put_int(check(emu_set_motion((int32_t)arg_int(a[0]), (int32_t)arg_int(a[1]), toml), "$emu_set_motion"));
    free(toml);
    return 0;
}

static PLI_INT32 count_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 2, "$emu_count"))
        return 0;
    int64_t n = emu_count((int32_t)arg_int(a[0]));
    if (n < 0)
        report("$emu_count");
    put_half(n, arg_int(a[1]));
    return 0;
}

static PLI_INT32 last_value_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 3, "$emu_last_value"))
        return 0;
    put_half(emu_last_value((int32_t)arg_int(a[0]), (int32_t)arg_int(a[1])), arg_int(a[2]));
    return 0;
}

static PLI_INT32 last_status_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 3, "$emu_last_status"))
        return 0;
    char *name = arg_str(a[2]);
    put_int(check(emu_last_status((int32_t)arg_int(a[0]), (int32_t)arg_int(a[1]), name), "$emu_last_status"));
    free(name);
    return 0;
}

static PLI_INT32 write_transcript_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 2, "$emu_write_transcript"))
        return 0;
    char *path = arg_str(a[1]);
    put_int(check(emu_write_transcript((int32_t)arg_int(a[0]), path), "$emu_write_transcript"));
    free(path);
    return 0;
}

static PLI_INT32 violations_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 1, "$emu_violations"))
        return 0;
    put_int((int32_t)emu_violations((int32_t)arg_int(a[0])));
    return 0;
}

static PLI_INT32 print_violations_calltf(PLI_BYTE8 *user) {
    (void)user;
    vpiHandle a[MAX_ARGS];
    if (wrong_count(args(a), 2, "$emu_print_violations"))
        return 0;
    int32_t h = (int32_t)arg_int(a[0]);
    /* The instance: the scope of the task that called us (the second
     * argument is an optional label printed after it). */
    vpiHandle scope = vpi_handle(vpiScope, vpi_handle(vpiSysTfCall, NULL));
    const char *inst = scope ? vpi_get_str(vpiFullName, scope) : "";
    char *who = arg_str(a[1]);
    char *p = who;
    while (*p == ' ')
        p++;
    int n = 0;
    for (;;) {
        const char *line = emu_take_violation(h);
        if (!line || !*line)
            break;
        vpi_printf("PROTOCOL VIOLATION by the master on %s%s%s %s\n", inst ? inst : "", *p ? " " : "", p, line);
        n++;
    }
    free(who);
    put_int(n);
    return 0;
}

static PLI_INT32 end_of_simulation(p_cb_data data) {
    (void)data;
    for (int i = 0; i < n_transcripts; i++)
        if (emu_write_transcript(transcripts[i].handle, transcripts[i].path) < 0)
            vpi_printf("ERROR: emulator transcript: %s\n", emu_last_error());
    return 0;
}

static void define(const char *name, PLI_INT32 (*calltf)(PLI_BYTE8 *)) {
    s_vpi_systf_data tf;
    memset(&tf, 0, sizeof tf);
    tf.type = vpiSysFunc;
    tf.sysfunctype = vpiIntFunc;
    tf.tfname = (PLI_BYTE8 *)name;
    tf.calltf = calltf;
    vpi_register_systf(&tf);
}

static void register_all(void) {
    define("$emu_open", open_calltf);
    define("$emu_step", step_calltf);
    define("$emu_set_position", set_position_calltf);
    define("$emu_set_motion", set_motion_calltf);
    define("$emu_set_status", set_status_calltf);
    define("$emu_schedule_fault", schedule_fault_calltf);
    define("$emu_count", count_calltf);
    define("$emu_last_value", last_value_calltf);
    define("$emu_last_status", last_status_calltf);
    define("$emu_write_transcript", write_transcript_calltf);
    define("$emu_violations", violations_calltf);
    define("$emu_print_violations", print_violations_calltf);

    s_cb_data cb;
    memset(&cb, 0, sizeof cb);
    cb.reason = cbEndOfSimulation;
    cb.cb_rtn = end_of_simulation;
    vpi_register_cb(&cb);
}

void (*vlog_startup_routines[])(void) = {register_all, 0};
