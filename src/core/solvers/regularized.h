/* src/core/solvers/regularized.h - internal: what the one-mass and the network regularized runs share. */
#ifndef DASHPOT_CORE_SOLVERS_REGULARIZED_H
#define DASHPOT_CORE_SOLVERS_REGULARIZED_H

#include <gsl/gsl_odeiv2.h>

#include "dashpot/spec.h"

/* The GSL odeiv2 stepper of a dp_stepper (regularized.c). */
const gsl_odeiv2_step_type *dp_regularized_step_type(dp_stepper s);

#endif
