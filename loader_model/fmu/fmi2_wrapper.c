/* FMI 2.0 Model Exchange wrapper around CasADi-generated code (loader_model.fmu).
 *
 * fmu_config.h (written by loader_model.fmu.build) defines MODEL_GUID and the sizes N_P, N_SET,
 * N_IN, N_X, N_Y, N_Z; fmu_model.h (CasADi CodeGenerator) declares fmu_ode(x, in, p) -> (xdot, y)
 * and fmu_start(p) -> (x0). Every Real lives in one array r[] indexed by its value reference:
 * plant parameters, controller parameters, inputs, states, derivatives, outputs, controller
 * states (loader_model/fmu/variables.py, closed_loop.py).
 *
 * With CLOSED_LOOP defined, r[VR_IN] is the held pump command, an output: at every sample
 * t0 + k T_s the FMU asks for a time event and fmu_sample(x, in, p, z) -> (z_next, u) updates
 * the controller's states and the command; fmu_ctrl_init(x, in, p) -> z0 starts the controller
 * at its fixed point (loader_model/fmu/closed_loop.py).
 */
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmu_config.h"
#include "fmu_model.h"

#define VR_IN (N_P + N_SET)
#define VR_X (VR_IN + N_IN)
#define VR_DX (VR_X + N_X)
#define VR_Y (VR_DX + N_X)
#define VR_Z (VR_Y + N_Y)
#define N_R (VR_Z + N_Z)

typedef enum { INSTANTIATED, INITIALIZATION, EVENT, CONTINUOUS, TERMINATED } Mode;

typedef struct {
    double r[N_R];
    double nominal[N_X];
    fmi2Boolean start_at_equilibrium;
    fmi2Boolean dirty;
    fmi2Real time;
    fmi2Real start_time;
    long samples; /* samples taken since start_time */
    double z_next[N_Z + 1];
    double command;
    Mode mode;
    fmi2CallbackFunctions callbacks;
    char *name;
    casadi_int *iw;
    casadi_real *w;
    const casadi_real **arg;
    casadi_real **res;
} Instance;

static const double START[N_R] = START_VALUES;
static const double NOMINAL[N_X] = NOMINAL_VALUES;

static void log_error(Instance *m, const char *message) {
    if (m->callbacks.logger)
        m->callbacks.logger(m->callbacks.componentEnvironment, m->name, fmi2Error, "error", message);
}

/* Evaluate derivatives and outputs from the current states, inputs and parameters. */
static fmi2Status evaluate(Instance *m) {
    if (!m->dirty) return fmi2OK;
    m->arg[0] = m->r + VR_X;
    m->arg[1] = m->r + VR_IN;
    m->arg[2] = m->r;
    m->res[0] = m->r + VR_DX;
    m->res[1] = m->r + VR_Y;
    if (fmu_ode(m->arg, m->res, m->iw, m->w, 0)) {
        log_error(m, "evaluation of the plant failed");
        return fmi2Error;
    }
    m->dirty = fmi2False;
    return fmi2OK;
}

static fmi2Status equilibrium(Instance *m) {
    if (!m->start_at_equilibrium) return fmi2OK;
    m->arg[0] = m->r;
    m->res[0] = m->r + VR_X;
    if (fmu_start(m->arg, m->res, m->iw, m->w, 0)) {
        log_error(m, "static equilibrium failed");
        return fmi2Error;
    }
    m->dirty = fmi2True;
    return fmi2OK;
}

#ifdef CLOSED_LOOP
/* One controller sample at the current time: z <- z_next, held command <- u. */
static fmi2Status sample(Instance *m) {
    m->arg[0] = m->r + VR_X;
    m->arg[1] = m->r + VR_IN;
    m->arg[2] = m->r;
    m->arg[3] = m->r + VR_Z;
    m->res[0] = m->z_next;
    m->res[1] = &m->command;
    if (fmu_sample(m->arg, m->res, m->iw, m->w, 0)) {
        log_error(m, "controller sample failed");
        return fmi2Error;
    }
    memcpy(m->r + VR_Z, m->z_next, N_Z * sizeof(double));
    m->r[VR_IN] = m->command;
    m->samples++;
    m->dirty = fmi2True;
    return fmi2OK;
}

static fmi2Status start_controller(Instance *m) {
    if (!(m->r[VR_TS] > 0.0)) {
        log_error(m, "controller.T_s must be > 0");
        return fmi2Error;
    }
    m->arg[0] = m->r + VR_X;
    m->arg[1] = m->r + VR_IN;
    m->arg[2] = m->r;
    m->res[0] = m->r + VR_Z;
    if (fmu_ctrl_init(m->arg, m->res, m->iw, m->w, 0)) {
        log_error(m, "controller start failed");
        return fmi2Error;
    }
    m->samples = 0;
    return sample(m); /* the sample at the start time */
}

static double next_sample_time(const Instance *m) {
    return m->start_time + (double)m->samples * m->r[VR_TS];
}
#endif

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String c2[]) {
    (void)c; (void)on; (void)n; (void)c2;
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                              fmi2String location, const fmi2CallbackFunctions *callbacks,
                              fmi2Boolean visible, fmi2Boolean logging) {
    (void)location; (void)visible; (void)logging;
    if (type != fmi2ModelExchange || !guid || strcmp(guid, MODEL_GUID) != 0) {
        if (callbacks && callbacks->logger)
            callbacks->logger(callbacks->componentEnvironment, name, fmi2Error, "error",
                              "wrong FMU type (only Model Exchange) or GUID");
        return NULL;
    }
    Instance *m = calloc(1, sizeof(Instance));
    if (!m) return NULL;
    casadi_int n_arg = 0, n_res = 0, n_iw = 0, n_w = 0, sizes[4][4];
    fmu_ode_work(&sizes[0][0], &sizes[0][1], &sizes[0][2], &sizes[0][3]);
    fmu_start_work(&sizes[1][0], &sizes[1][1], &sizes[1][2], &sizes[1][3]);
#ifdef CLOSED_LOOP
    fmu_sample_work(&sizes[2][0], &sizes[2][1], &sizes[2][2], &sizes[2][3]);
    fmu_ctrl_init_work(&sizes[3][0], &sizes[3][1], &sizes[3][2], &sizes[3][3]);
    int n_functions = 4;
#else
    int n_functions = 2;
#endif
    for (int i = 0; i < n_functions; i++) {
        if (sizes[i][0] > n_arg) n_arg = sizes[i][0];
        if (sizes[i][1] > n_res) n_res = sizes[i][1];
        if (sizes[i][2] > n_iw) n_iw = sizes[i][2];
        if (sizes[i][3] > n_w) n_w = sizes[i][3];
    }
    m->arg = calloc(n_arg + 1, sizeof(casadi_real *));
    m->res = calloc(n_res + 1, sizeof(casadi_real *));
    m->iw = calloc(n_iw + 1, sizeof(casadi_int));
    m->w = calloc(n_w + 1, sizeof(casadi_real));
    m->name = calloc(strlen(name ? name : "") + 1, 1);
    if (!m->arg || !m->res || !m->iw || !m->w || !m->name) {
        free(m->arg); free(m->res); free(m->iw); free(m->w); free(m->name); free(m);
        return NULL;
    }
    strcpy(m->name, name ? name : "");
    if (callbacks) m->callbacks = *callbacks;
    memcpy(m->r, START, sizeof(START));
    memcpy(m->nominal, NOMINAL, sizeof(NOMINAL));
    m->start_at_equilibrium = fmi2True;
    m->dirty = fmi2True;
    m->mode = INSTANTIATED;
    return m;
}

void fmi2FreeInstance(fmi2Component c) {
    Instance *m = c;
    if (!m) return;
    free(m->arg); free(m->res); free(m->iw); free(m->w); free(m->name); free(m);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tolerance_defined, fmi2Real tolerance,
                               fmi2Real start, fmi2Boolean stop_defined, fmi2Real stop) {
    (void)tolerance_defined; (void)tolerance; (void)stop_defined; (void)stop;
    ((Instance *)c)->time = start;
    ((Instance *)c)->start_time = start;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    Instance *m = c;
    m->mode = INITIALIZATION;
    return equilibrium(m);
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    Instance *m = c;
    fmi2Status status = equilibrium(m);
#ifdef CLOSED_LOOP
    if (status == fmi2OK) status = start_controller(m);
#endif
    m->mode = EVENT;
    return status;
}

fmi2Status fmi2Terminate(fmi2Component c) { ((Instance *)c)->mode = TERMINATED; return fmi2OK; }

fmi2Status fmi2Reset(fmi2Component c) {
    Instance *m = c;
    memcpy(m->r, START, sizeof(START));
    m->start_at_equilibrium = fmi2True;
    m->dirty = fmi2True;
    m->mode = INSTANTIATED;
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    Instance *m = c;
    for (size_t i = 0; i < n; i++) {
        if (vr[i] >= N_R) { log_error(m, "unknown Real value reference"); return fmi2Error; }
        if (vr[i] >= VR_DX && evaluate(m) != fmi2OK) return fmi2Error;
        v[i] = m->r[vr[i]];
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                       const fmi2Real v[]) {
    Instance *m = c;
    for (size_t i = 0; i < n; i++) {
#ifdef CLOSED_LOOP
        if (vr[i] == VR_IN) { log_error(m, "V_p_ref is the controller's output"); return fmi2Error; }
#endif
        if (vr[i] >= VR_DX) { log_error(m, "Real value reference cannot be set"); return fmi2Error; }
        if (vr[i] < VR_IN && m->mode != INSTANTIATED && m->mode != INITIALIZATION) {
            log_error(m, "parameters are fixed after initialization");
            return fmi2Error;
        }
        m->r[vr[i]] = v[i];
    }
    m->dirty = fmi2True;
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          fmi2Boolean v[]) {
    Instance *m = c;
    for (size_t i = 0; i < n; i++) {
        if (vr[i] != 0) { log_error(m, "unknown Boolean value reference"); return fmi2Error; }
        v[i] = m->start_at_equilibrium;
    }
    return fmi2OK;
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Boolean v[]) {
    Instance *m = c;
    for (size_t i = 0; i < n; i++) {
        if (vr[i] != 0) { log_error(m, "unknown Boolean value reference"); return fmi2Error; }
        m->start_at_equilibrium = v[i];
    }
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          fmi2Integer v[]) {
    (void)v;
    if (n) { log_error(c, "the FMU has no Integer variables"); (void)vr; return fmi2Error; }
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Integer v[]) {
    (void)v;
    if (n) { log_error(c, "the FMU has no Integer variables"); (void)vr; return fmi2Error; }
    return fmi2OK;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                         fmi2String v[]) {
    (void)v;
    if (n) { log_error(c, "the FMU has no String variables"); (void)vr; return fmi2Error; }
    return fmi2OK;
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                         const fmi2String v[]) {
    (void)v;
    if (n) { log_error(c, "the FMU has no String variables"); (void)vr; return fmi2Error; }
    return fmi2OK;
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)s; log_error(c, "not supported"); return fmi2Error; }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) { (void)s; log_error(c, "not supported"); return fmi2Error; }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)s; log_error(c, "not supported"); return fmi2Error; }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n) { (void)s; (void)n; log_error(c, "not supported"); return fmi2Error; }
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) { (void)s; (void)b; (void)n; log_error(c, "not supported"); return fmi2Error; }
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s) { (void)s; (void)b; (void)n; log_error(c, "not supported"); return fmi2Error; }

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                        const fmi2ValueReference z[], size_t nz,
                                        const fmi2Real dv[], fmi2Real df[]) {
    (void)u; (void)nu; (void)z; (void)nz; (void)dv; (void)df;
    log_error(c, "directional derivatives are not provided");
    return fmi2Error;
}

fmi2Status fmi2EnterEventMode(fmi2Component c) { ((Instance *)c)->mode = EVENT; return fmi2OK; }

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info) {
    Instance *m = c;
    (void)m;
    info->newDiscreteStatesNeeded = fmi2False;
    info->terminateSimulation = fmi2False;
    info->nominalsOfContinuousStatesChanged = fmi2False;
    info->valuesOfContinuousStatesChanged = fmi2False;
    info->nextEventTimeDefined = fmi2False;
    info->nextEventTime = 0.0;
#ifdef CLOSED_LOOP
    /* sample when the time has reached the next sample (to a billionth of the period) */
    if (m->time >= next_sample_time(m) - 1e-9 * m->r[VR_TS] && sample(m) != fmi2OK)
        return fmi2Error;
    info->nextEventTimeDefined = fmi2True;
    info->nextEventTime = next_sample_time(m);
#endif
    return fmi2OK;
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { ((Instance *)c)->mode = CONTINUOUS; return fmi2OK; }

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean no_prior, fmi2Boolean *enter,
                                       fmi2Boolean *terminate) {
    (void)c; (void)no_prior;
    *enter = fmi2False;
    *terminate = fmi2False;
    return fmi2OK;
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time) { ((Instance *)c)->time = time; return fmi2OK; }

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx) {
    Instance *m = c;
    if (nx != N_X) { log_error(m, "wrong number of states"); return fmi2Error; }
    memcpy(m->r + VR_X, x, N_X * sizeof(double));
    m->dirty = fmi2True;
    return fmi2OK;
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real dx[], size_t nx) {
    Instance *m = c;
    if (nx != N_X) { log_error(m, "wrong number of states"); return fmi2Error; }
    if (evaluate(m) != fmi2OK) return fmi2Error;
    memcpy(dx, m->r + VR_DX, N_X * sizeof(double));
    return fmi2OK;
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real z[], size_t nz) {
    (void)c; (void)z;
    return nz == 0 ? fmi2OK : fmi2Error;
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    Instance *m = c;
    if (nx != N_X) { log_error(m, "wrong number of states"); return fmi2Error; }
    memcpy(x, m->r + VR_X, N_X * sizeof(double));
    return fmi2OK;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    Instance *m = c;
    if (nx != N_X) { log_error(m, "wrong number of states"); return fmi2Error; }
    memcpy(x, m->nominal, N_X * sizeof(double));
    return fmi2OK;
}
