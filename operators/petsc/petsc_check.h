// operators/petsc/petsc_check.h — internal: PETSc error codes to SolverError (the engine's
// sources only).
#pragma once

#include <petscsys.h>

namespace polydec::petsc {

// Throws SolverError naming `what` and PETSc's message when code is not 0.
void check(PetscErrorCode code, const char* what);

}  // namespace polydec::petsc
