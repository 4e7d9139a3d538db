/* src/core/runs/run_table.h - internal: the one table of run types. */
#ifndef DASHPOT_CORE_RUNS_RUN_TABLE_H
#define DASHPOT_CORE_RUNS_RUN_TABLE_H

#include "record/sink.h"

/* The run type that solves a spec: the first row of the table whose model family and solver match. */
const dp_run_type *dp_run_type_of(const dp_spec *spec);

#endif
