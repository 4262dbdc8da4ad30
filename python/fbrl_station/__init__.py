# SPDX-License-Identifier: MIT
"""fbrl_station - fbrl-station, a SiLA 2 server for one CRS robot arm, written on the fbrl
bindings (docs/sila.md). python3 -m fbrl_station --help."""
