// operators/detail/volume_refinement_in_use.h — the volume refinement a builder works with: the
// caller's (VolumeOperatorOptions::refinement) or, without one, one built here.
#pragma once

#include <utility>

#include "polydec/dec/volume/refinement.h"

namespace polydec::detail {

class VolumeRefinementInUse {
 public:
  // The caller's refinement `given` (not copied), or refine_volume(mesh, options) when it is null.
  VolumeRefinementInUse(const VolumeMesh& mesh, const VolumeRefinement* given,
                        const VolumeRefinementOptions& options = {})
      : given_(given) {
    if (!given_) own_ = refine_volume(mesh, options);
  }

  // The refinement in use.
  const VolumeRefinement& get() const { return given_ ? *given_ : own_; }

  // The refinement in use for a caller to keep (OperatorSet::volume_refinement): a copy of the
  // caller's, or the one built here moved out (get() is then no longer valid).
  VolumeRefinement release() { return given_ ? *given_ : std::move(own_); }

 private:
  const VolumeRefinement* given_;
  VolumeRefinement own_;
};

}  // namespace polydec::detail
