// The records of a bag file (format 2.0) checked before librosbag reads them: librosbag trusts
// every length and offset it reads, and a damaged one makes it allocate gigabytes or read past
// its buffers (a crash, or another message's bytes taken for this one's).
#pragma once

#include <string>

namespace mbk_offline {

// Throws std::invalid_argument naming `path` and the byte where the bag is damaged when:
// - a top-level record (header length, header, data length, data) goes beyond the file;
// - a record inside a chunk goes beyond the chunk's data (uncompressed: as given in its header);
// - an index entry after a chunk points at no record of that chunk.
// A chunk that does not decompress is left to librosbag, which refuses each of its messages.
// Not a bag (no "#ROSBAG V2.0" line): nothing checked, rosbag's error to give.
void check_bag_records(const std::string& path);

}  // namespace mbk_offline
