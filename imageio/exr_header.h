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

// Who made the file: the standard chromaticities (Rec.709 with D65), capDate and utcOffset of
// now, owner and comments when set, and tessera's version, instruction set and command line.
void insert_provenance(Imf::Header& header, const FrameMetadata& m);

// The attributes that describe the file's layout rather than the frame: channels, windows,
// compression, line order, tiles, part names and types.
bool is_layout_attribute(const std::string& name);

// Every attribute of `header` of a type HeaderAttribute holds, but the file's layout
// (channels, windows, compression, ...), which belongs to the pixels, not to the frame.
std::vector<HeaderAttribute> header_attributes(const Imf::Header& header);
void insert_attributes(Imf::Header& header, const std::vector<HeaderAttribute>& attributes);

// The attributes insert_frame_metadata writes for `m`, as a list.
std::vector<HeaderAttribute> frame_header_attributes(const FrameMetadata& m, int samples_per_pixel);

// Inserts every attribute of `m` (and the standard ones: chromaticities Rec.709 with D65,
// capDate and utcOffset of now) into `header`.
void insert_frame_metadata(Imf::Header& header, const FrameMetadata& m, int samples_per_pixel);

}  // namespace tessera
