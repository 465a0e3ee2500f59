// The AutoDiff instantiations of the reprojection factors for PixelResidual.
#include "reprojection_factors_impl.h"

namespace trigrav {

template class YawOnlyReprojectionError<PixelResidual>;
template class ReprojectionError<PixelResidual>;
template class ReferenceReprojectionError<PixelResidual>;

}  // namespace trigrav
