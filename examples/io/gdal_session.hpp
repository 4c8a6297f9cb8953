// SPDX-License-Identifier: Apache-2.0
// What every GDAL/OGR user in examples/io needs (only when built with GDAL): the drivers registered once, GDAL's
// own stderr reports silenced while a call runs (its errors become our exceptions), its last message, a
// configuration option set for one thread, and an owning pointer to an OGR spatial reference.
#pragma once

#ifdef LIDARFX_HAVE_GDAL
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <memory>
#include <mutex>
#include <optional>
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

/// Sets a GDAL configuration option for the calling thread while alive; its thread-local value before comes back
/// after.
class thread_config_option {
public:
    thread_config_option(const char* key, const char* value) : key_(key)
    {
        if (const char* before = CPLGetThreadLocalConfigOption(key, nullptr)) before_ = before;
        CPLSetThreadLocalConfigOption(key, value);
    }
    ~thread_config_option() { CPLSetThreadLocalConfigOption(key_, before_ ? before_->c_str() : nullptr); }
    thread_config_option(const thread_config_option&) = delete;
    thread_config_option& operator=(const thread_config_option&) = delete;

private:
    const char* key_;
    std::optional<std::string> before_;
};

/// An OGR spatial reference owned by a unique_ptr.
struct srs_deleter {
    void operator()(void* srs) const { OSRDestroySpatialReference(static_cast<OGRSpatialReferenceH>(srs)); }
};
using srs_ptr = std::unique_ptr<void, srs_deleter>;

/// GDAL's last error message as " (message)", or "" when it has none.
inline std::string gdal_message()
{
    const char* m = CPLGetLastErrorMsg();
    return m != nullptr && *m != '\0' ? std::string(" (") + m + ")" : std::string();
}

}  // namespace lidarfx::io
#endif
