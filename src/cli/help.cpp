// Copyright (c) 2026 SpringMotion developers.
#include "commands.h"

#include <spring_motion/stiffness/model_by_name.h>

#include <regex>

namespace spring_motion {
namespace cli {
namespace {

// The names of the model table, comma-separated, wrapped after `width`
// characters, each line after the first starting with `indent`.
std::string model_name_list(const std::string& indent, std::size_t width)
{
  std::string text, line;
  const auto& names = model_names();
  for(std::size_t i = 0; i < names.size(); ++i) {
    const std::string word = names[i] + (i + 1 < names.size() ? "," : "");
    if(!line.empty() && line.size() + 1 + word.size() > width) {
      text += line + "\n" + indent;
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return text + line;
}

// One line per model of the table: name, where it works, summary.
std::string model_table_lines(const std::string& indent)
{
  std::string text;
  for(const auto& e : model_table()) {
    text += indent + e.name;
    if(!(e.in_2d && e.in_3d))
      text += e.in_2d ? " (2D only)" : " (3D only)";
    text += "\n" + indent + "    " + e.summary + "\n";
  }
  return text;
}

} // namespace

std::string main_help()
{
  return R"(usage: spring-motion COMMAND [OPTIONS]

Spring-analogy mesh motion for 2D triangle and 3D tetrahedral meshes.

commands:
  deform MESH ...   move the boundary parts named by --moving and the rest of the
                    mesh with them; write VTU / PVD / Medit and a JSON report
  check MESH        validity (exact orientation) and quality (equiangle skewness)
                    of a mesh as it is
  convert MESH OUT  the same mesh in another format (.mesh, .msh, .su2 or .vtu)

  spring-motion COMMAND --help    options of a command
  spring-motion --version         the version

Meshes read: Medit ASCII (.mesh, Dimension 2 or 3), Gmsh 2.2 / 4.1 ASCII and
binary (.msh), SU2 (.su2). Written: .vtu, .pvd, .mesh, .msh (Gmsh 4.1 ASCII), .su2.
Stiffness models (deform --model):
  )" + model_name_list("  ", 76) + R"(
Exit status: 0 success, 1 bad input (nothing written), 2 bad command line,
3 motion stopped at an inverted step / invalid mesh, 4 internal error,
130 interrupted (outputs removed).
See docs/cli.md.
)";
}

std::string deform_help()
{
  return R"(usage: spring-motion deform MESH --moving REF[,REF...] [--fixed REF[,REF...]]
                            [--sliding REF[,REF...]] MOTION
                            [--steps N] [--model NAME] [--solver cg|cg-sgs|sor|paper] [--omega W]
                            [--tolerance E] [--max-iterations N] [--max-substep-halvings K]
                            [--threads T] [--output OUT]... [--every K] [--report R.json]
                            [--quiet | --progress]

Moves the vertices of the boundary parts REF by MOTION in N increments; the
interior follows as a network of springs (stiffness from the model, recomputed
at every step). After every step each element's orientation is checked with
exact predicates; a step that inverts one stops the run at the last valid state.

MESH      Medit .mesh, Gmsh .msh (2.2 or 4.1, ASCII or binary) or SU2 .su2. A
          mesh of triangles whose z are all 0 is 2D; tetrahedra make it 3D.
REF       a boundary label: a number (Medit reference, Gmsh physical tag) or a
          Gmsh physical name, e.g. --moving airfoil or --moving 1,2.

boundary rules:
  - vertices on a --moving part move with the motion;
  - without --fixed, every other boundary vertex is fixed (stays in place);
  - with --fixed, only vertices on those parts are fixed, and boundary vertices
    on neither kind of part are free (they follow the springs);
  - a vertex on both a moving and a fixed part MOVES (moving wins);
  - vertices on a --sliding part (a plane in 3D, a straight line in 2D: a
    symmetry plane) follow the springs within that plane and stay on it
    exactly; on a sliding and a moving part a vertex moves, on a sliding and
    a fixed part (or, without --fixed, any part that does not slide) it stays;
    on two sliding parts it slides along their intersection;
  - interior vertices are free. Free vertices must be connected to a moving or
    fixed vertex, else the run stops with an error.

MOTION (exactly one):
  --pitch DEG --center X,Y[,Z] [--axis AX,AY,AZ]
          rotation about CENTER by alpha(t) = DEG sin(pi t / 2) (the quarter-sine
          schedule), t = i/N at step i; 2D: counter-clockwise about +z; 3D: about
          AXIS (default 0,0,1), right-hand rule
  --translate DX,DY[,DZ]
          rigid translation, t * (DX, DY, DZ) at step i
  --displacement FILE
          one line 'ID DX DY [DZ]' per moving vertex (ID: Medit 1-based vertex
          index, Gmsh node tag), applied as t * displacement; '#' starts a comment.
          With --moving, every vertex of those parts needs a line; without it the
          listed vertices are the moving ones.

options:
  --steps N            increments (default 100)
  --model NAME         stiffness model (default grid_scaled), one of:
)" + model_table_lines("                         ") + R"(  --solver NAME        cg: conjugate gradients preconditioned by a multigrid
                       cycle, stopped when the estimated error <= tolerance
                       (default); cg-sgs: the same with a symmetric
                       Gauss-Seidel sweep as the preconditioner;
                       sor: SOR with --omega, same stopping rule;
                       paper: SOR stopped when no component changes by more than
                       5e-6 (the paper's Eq. 12)
  --omega W            SOR relaxation factor in (0, 2) (default 1; implies sor)
  --tolerance E        solver tolerance in mesh length units (default 1e-6; paper: 5e-6)
  --max-iterations N   iteration cap per solve (default 100000)
  --max-substep-halvings K
                       retry an inverting step as 2, 4, ... 2^K substeps (default 0)
  --threads T          OpenMP threads (default: OpenMP's team or one thread,
                       chosen step by step by measuring both; one thread wins
                       when other processes keep the cores busy); T caps the
                       whole run, reading, checks and output included
  --backend NAME       shared (default): this library's solver; petsc: the
                       mesh partitioned over the MPI ranks of mpiexec -n N,
                       each step's system solved by PETSc (CG + GAMG) to the
                       same error estimate (a build with
                       SPRING_MOTION_WITH_PETSC=ON; docs/scaling.md)
  --output OUT         by extension, may be repeated:
                       .vtu   the final mesh, with point 'displacement' and cell
                              'skewness' (R), 'valid' (1/0) and 'label'
                       .pvd   a ParaView time series: OUT_<step>.vtu beside it for
                              step 0, every K-th step and the last valid step
                       .mesh  the final mesh as Medit, labels kept
                       .msh   the final mesh as Gmsh 4.1 ASCII, labels kept
                       .su2   the final mesh as SU2, labels kept as markers
  --every K            steps between .pvd frames (default 1)
  --report R.json      the run's JSON report (format spring_motion.report/1)
  --quiet              no progress bar
  --progress           a progress bar on stderr even when it is not a terminal

The progress bar is drawn on stderr only when stderr is a terminal. One summary
line is always printed on stdout. Outputs are written to temporary files and
renamed, so a failed run leaves no partial output; the input is never modified.
When the motion stops at an inverted step, the outputs hold the last valid
state and the exit status is 3.

exit status: 0 completed, 1 bad input (nothing written), 2 bad command line,
3 stopped at an inverted step, 4 internal error, 130 interrupted (Ctrl-C:
the outputs written so far are removed).

example:
  spring-motion deform wing.msh --moving airfoil --pitch 30 --center 0.25,0 \
      --steps 100 --output wing.pvd --every 5 --report wing.json
)";
}

std::string check_help()
{
  return R"(usage: spring-motion check MESH

Reads MESH (Medit .mesh, Gmsh .msh ASCII or binary, SU2 .su2) and prints: dimension and sizes, every
label with what it marks, orientation counts, and, for a valid mesh, element
size and edge length ranges and histograms of the equiangle skewness R (Eq. 13
of the paper; 0 equilateral, 1 degenerate) over all elements and over those
touching the boundary.

An element is degenerate when its exact orientation is zero, inverted when it
overlaps a neighbour across a shared edge (2D) or face (3D).

exit status: 0 valid, 1 bad input, 2 bad command line, 3 degenerate or inverted
elements (listed on stderr with their lines; for a binary .msh, the byte
offsets at which they are written).
)";
}

std::string convert_help()
{
  return R"(usage: spring-motion convert MESH OUT

Writes the mesh of MESH (Medit .mesh, Gmsh .msh ASCII or binary, SU2 .su2)
to OUT, by extension: .mesh (Medit ASCII), .msh (Gmsh 4.1 ASCII) or .su2
(SU2), each with the labels and coordinates that read back bit for bit; or
.vtu (with the element labels as cell data 'label').

exit status: 0 written, 1 bad input (nothing written), 2 bad command line.
)";
}

std::string without_source_location(const std::string& message)
{
  static const std::regex suffix(R"( \[[^\[\]]*:[0-9]+\]$)");
  return std::regex_replace(message, suffix, "");
}

} // namespace cli
} // namespace spring_motion
