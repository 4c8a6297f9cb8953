# SPDX-License-Identifier: Apache-2.0
"""One module per Processing algorithm of the lidarfx provider."""
