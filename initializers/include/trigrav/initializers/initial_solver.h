#ifndef TRIGRAV_INITIALIZERS_INITIAL_SOLVER_H_
#define TRIGRAV_INITIALIZERS_INITIAL_SOLVER_H_

#include <array>
#include <string>

namespace trigrav {

// The minimal solvers a robust estimate can be seeded with: the paper's methods and its baselines.
// Each has one short name (InitialSolverName), used by every tool, CSV, plot and table.
enum class InitialSolver {
  kTrifocal3pt,        // "3pt": decoupled 3-point, gravity-aware (trifocal_3pt.h); the default
  kTrifocal3ptSextic,  // "3pt-sextic": the paper's 3-point system, gravity-aware
  kTrifocal4pt,        // "4pt": the paper's 4-point linear trifocal solver, gravity-aware
  kTrifocalLinear,     // "7pt-linear": normalised linear trifocal tensor, 7 triplets
  kEssential5pt,       // "5pt": Nister's five-point on pairs (1,2) and (1,3)
  kEssential8pt,       // "8pt": normalised eight-point on pairs (1,2) and (1,3)
};

// Every initial solver, in the order above: the one list tools and tests iterate.
inline constexpr std::array<InitialSolver, 6> kInitialSolvers = {
    InitialSolver::kTrifocal3pt,  InitialSolver::kTrifocal3ptSextic,
    InitialSolver::kTrifocal4pt,  InitialSolver::kTrifocalLinear,
    InitialSolver::kEssential5pt, InitialSolver::kEssential8pt};

// "3pt", "3pt-sextic", "4pt", "7pt-linear", "5pt", "8pt". Throws std::invalid_argument for a value
// outside the enum.
const char* InitialSolverName(InitialSolver solver);
// Inverse of InitialSolverName; false (and *solver untouched) for an unknown name.
bool ParseInitialSolver(const std::string& name, InitialSolver* solver);
// The names of kInitialSolvers joined by ", " (for help texts and error messages).
std::string InitialSolverNames();
// Triplets in a minimal sample of the method (3, 3, 4, 7, 5, 8).
int MinimalSampleSize(InitialSolver solver);
// True for the methods that use the gravity (3pt, 3pt-sextic, 4pt).
bool UsesGravity(InitialSolver solver);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_INITIAL_SOLVER_H_
