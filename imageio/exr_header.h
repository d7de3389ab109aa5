// The header attributes of a frame's EXR: tessera's render metadata, and OpenEXR's standard
// attributes where one exists for the information (chromaticities, capDate and utcOffset,
// owner, comments, worldToCamera, worldToNDC).
#pragma once

#include <ctime>
#include <string>

#include <OpenEXR/ImfForward.h>

#include "imageio/image_output.h"

namespace tessera {

// `t` in OpenEXR's capDate format, "YYYY:MM:DD hh:mm:ss" in local time, and the standard
// utcOffset: seconds to add to that local time to get UTC.
std::string exr_cap_date(std::time_t t);
float exr_utc_offset(std::time_t t);

// Inserts every attribute of `m` (and the standard ones: chromaticities Rec.709 with D65,
// capDate and utcOffset of now) into `header`.
void insert_frame_metadata(Imf::Header& header, const FrameMetadata& m, int samples_per_pixel);

}  // namespace tessera
