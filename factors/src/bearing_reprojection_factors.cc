// The AutoDiff instantiations of the reprojection factors for BearingResidual.
#include "reprojection_factors_impl.h"

namespace trigrav {

template class YawOnlyReprojectionError<BearingResidual>;
template class ReprojectionError<BearingResidual>;
template class ReferenceReprojectionError<BearingResidual>;

}  // namespace trigrav
