// The forms the stability suite runs: keyword sets of the library's shaders and of the probes
// that include them.
#pragma once

#include "stability/case.h"

namespace xshade::stability {

// Every shader's own seed form: no keyword.
inline const Form kSeed{"seed", {}, true};
// The toon's and the depth of field's guards: _GUARDED alone.
inline const Form kGuardedOnly{"guarded", {"_GUARDED"}, false};

// The Cook-Torrance lobe. "guarded" is SHADERS.md's guarded form: the guards of hazards 1-4 and the Lagrange D of
// hazard 8. The material_grid_guarded scene's form keeps the seed's D with the guards: stable in
// fp32, and SHADERS.md predicts its D overflows fp16.
inline const Form kGuardsSeedD{"guards, seed D", {"_GUARDED"}, true};
inline const Form kGuarded{"guarded", {"_GUARDED", "_D_GGX_LAGRANGE"}, false};
inline const Form kGuardedSmith{"guarded, Smith", {"_GUARDED", "_D_GGX_LAGRANGE", "_G_SMITH_CORRELATED"}, false};
inline const Form kGuardedSmithFast{"guarded, fast Smith", {"_GUARDED", "_D_GGX_LAGRANGE", "_G_SMITH_FAST"}, false};
inline const Form kGuardedSG{"guarded, SG Fresnel", {"_GUARDED", "_D_GGX_LAGRANGE", "_F_SPHERICAL_GAUSSIAN"}, false};
inline const Form kGuardedExactF{"guarded, exact Fresnel", {"_GUARDED", "_D_GGX_LAGRANGE", "_F_EXACT"}, false};

}  // namespace xshade::stability
