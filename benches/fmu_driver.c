/* The FMU's C ABI as a co-simulation master drives it (issue 28):
 * dlopen of the built library, fmi2Instantiate, SetupExperiment, the
 * parameters set in initialisation mode, then a loop of fmi2SetReal(heave)
 * and fmi2DoStep at a fixed communication step, reading top_tension after
 * each step. No interpreter in the loop; compiled by benches/fmu.rs with cc.
 *
 * usage: fmu_driver LIB GUID VR_HEAVE VR_TOP_TENSION COMM_STEP DURATION
 *                   AMPLITUDE PERIOD RAMP WINDOW_START REPEATS
 *                   [r:VR=VALUE | i:VR=VALUE | b:VR=VALUE]...
 *
 * The heave is the CLI's (`riser run --heave A,T --ramp R`): A r(t) sin(2π t/T),
 * r = ½(1 − cos(π t/R)) for t < R, 1 after; the master gives its value at the
 * start of each communication step. Prints one line per repeat:
 *   wall_s <seconds of the SetReal+DoStep+GetReal loop> min <N> mean <N> max <N> steps <n>
 * with the top tension's min, mean and max over the communication points at
 * t >= WINDOW_START. Exit status 1 on any FMI error. */
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef void *fmi2Component;
typedef unsigned int fmi2ValueReference;
typedef int fmi2Status;
typedef void (*fmi2CallbackLogger)(void *, const char *, fmi2Status, const char *, const char *, ...);
typedef struct {
    fmi2CallbackLogger logger;
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(void *, fmi2Status);
    void *componentEnvironment;
} fmi2CallbackFunctions;

typedef fmi2Component (*Instantiate)(const char *, int, const char *, const char *, const fmi2CallbackFunctions *,
                                     int, int);
typedef void (*FreeInstance)(fmi2Component);
typedef fmi2Status (*SetupExperiment)(fmi2Component, int, double, double, int, double);
typedef fmi2Status (*Mode)(fmi2Component);
typedef fmi2Status (*SetReal)(fmi2Component, const fmi2ValueReference *, size_t, const double *);
typedef fmi2Status (*SetInt)(fmi2Component, const fmi2ValueReference *, size_t, const int *);
typedef fmi2Status (*GetReal)(fmi2Component, const fmi2ValueReference *, size_t, double *);
typedef fmi2Status (*DoStep)(fmi2Component, double, double, int);

static void logger(void *env, const char *name, fmi2Status status, const char *category, const char *fmt, ...) {
    (void)env;
    if (status < 2) return; /* OK and Warning: quiet */
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "[%s %s %d] ", name, category, status);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
}

static void *sym(void *lib, const char *name) {
    void *p = dlsym(lib, name);
    if (!p) {
        fprintf(stderr, "fmu_driver: %s not exported\n", name);
        exit(1);
    }
    return p;
}

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double heave(double t, double a, double period, double ramp) {
    const double pi = 3.14159265358979323846;
    double r = 1.0;
    if (ramp > 0.0 && t < ramp) r = 0.5 * (1.0 - cos(pi / ramp * t));
    return a * r * sin(2.0 * pi / period * t);
}

#define CHECK(call)                                                       \
    do {                                                                  \
        fmi2Status s_ = (call);                                           \
        if (s_ != 0) {                                                    \
            fprintf(stderr, "fmu_driver: %s returned %d\n", #call, s_);   \
            exit(1);                                                      \
        }                                                                 \
    } while (0)

int main(int argc, char **argv) {
    if (argc < 12) {
        fprintf(stderr, "usage: %s LIB GUID VR_HEAVE VR_TOP_TENSION COMM_STEP DURATION AMPLITUDE PERIOD RAMP "
                        "WINDOW_START REPEATS [r:VR=VALUE|i:VR=VALUE|b:VR=VALUE]...\n", argv[0]);
        return 2;
    }
    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "fmu_driver: %s\n", dlerror());
        return 1;
    }
    Instantiate instantiate = (Instantiate)sym(lib, "fmi2Instantiate");
    FreeInstance free_instance = (FreeInstance)sym(lib, "fmi2FreeInstance");
    SetupExperiment setup = (SetupExperiment)sym(lib, "fmi2SetupExperiment");
    Mode enter = (Mode)sym(lib, "fmi2EnterInitializationMode");
    Mode exit_init = (Mode)sym(lib, "fmi2ExitInitializationMode");
    Mode terminate = (Mode)sym(lib, "fmi2Terminate");
    SetReal set_real = (SetReal)sym(lib, "fmi2SetReal");
    SetInt set_int = (SetInt)sym(lib, "fmi2SetInteger");
    SetInt set_bool = (SetInt)sym(lib, "fmi2SetBoolean");
    GetReal get_real = (GetReal)sym(lib, "fmi2GetReal");
    DoStep do_step = (DoStep)sym(lib, "fmi2DoStep");

    const char *guid = argv[2];
    fmi2ValueReference vr_heave = (fmi2ValueReference)atoi(argv[3]);
    fmi2ValueReference vr_tension = (fmi2ValueReference)atoi(argv[4]);
    double h = atof(argv[5]), duration = atof(argv[6]);
    double amp = atof(argv[7]), period = atof(argv[8]), ramp = atof(argv[9]), window = atof(argv[10]);
    int repeats = atoi(argv[11]);
    long n = lround(duration / h);
    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};

    for (int rep = 0; rep < repeats; rep++) {
        fmi2Component c = instantiate("bench", 1, guid, NULL, &cb, 0, 0);
        if (!c) {
            fprintf(stderr, "fmu_driver: fmi2Instantiate failed\n");
            return 1;
        }
        CHECK(setup(c, 0, 0.0, 0.0, 1, duration));
        CHECK(enter(c));
        for (int k = 12; k < argc; k++) {
            char kind = argv[k][0];
            fmi2ValueReference vr = (fmi2ValueReference)strtoul(argv[k] + 2, NULL, 10);
            const char *eq = strchr(argv[k], '=');
            if (!eq || argv[k][1] != ':') {
                fprintf(stderr, "fmu_driver: bad parameter %s\n", argv[k]);
                return 2;
            }
            if (kind == 'r') {
                double v = atof(eq + 1);
                CHECK(set_real(c, &vr, 1, &v));
            } else if (kind == 'i' || kind == 'b') {
                int v = atoi(eq + 1);
                CHECK(kind == 'i' ? set_int(c, &vr, 1, &v) : set_bool(c, &vr, 1, &v));
            }
        }
        double u0 = heave(0.0, amp, period, ramp);
        CHECK(set_real(c, &vr_heave, 1, &u0));
        CHECK(exit_init(c));
        double mn = INFINITY, mx = -INFINITY, sum = 0.0;
        long count = 0;
        double t0 = now();
        for (long k = 0; k < n; k++) {
            double t = k * h;
            double u = heave(t, amp, period, ramp);
            CHECK(set_real(c, &vr_heave, 1, &u));
            CHECK(do_step(c, t, h, 1));
            double tension;
            CHECK(get_real(c, &vr_tension, 1, &tension));
            if ((k + 1) * h >= window - 1e-9) {
                mn = fmin(mn, tension);
                mx = fmax(mx, tension);
                sum += tension;
                count++;
            }
        }
        double wall = now() - t0;
        CHECK(terminate(c));
        free_instance(c);
        printf("wall_s %.6f min %.17g mean %.17g max %.17g steps %ld\n", wall, mn, sum / count, mx, n);
        fflush(stdout);
    }
    return 0;
}
