// SPDX-License-Identifier: Apache-2.0
// What every GDAL/OGR user in examples/io needs (only when built with GDAL): the drivers registered once, GDAL's
// own stderr reports silenced while a call runs (its errors become our exceptions), and its last message.
#pragma once

#ifdef LIDARFX_HAVE_GDAL
#include <cpl_error.h>
#include <gdal.h>

#include <mutex>
#include <string>

namespace lidarfx::io {

/// Registers GDAL's and OGR's drivers, once per process (safe from several threads).
inline void register_gdal_drivers()
{
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

/// Silences GDAL's default stderr reporting while alive and clears its last error.
struct quiet_gdal {
    quiet_gdal()
    {
        CPLPushErrorHandler(CPLQuietErrorHandler);
        CPLErrorReset();
    }
    ~quiet_gdal() { CPLPopErrorHandler(); }
    quiet_gdal(const quiet_gdal&) = delete;
    quiet_gdal& operator=(const quiet_gdal&) = delete;
};

/// GDAL's last error message as " (message)", or "" when it has none.
inline std::string gdal_message()
{
    const char* m = CPLGetLastErrorMsg();
    return m != nullptr && *m != '\0' ? std::string(" (") + m + ")" : std::string();
}

}  // namespace lidarfx::io
#endif
