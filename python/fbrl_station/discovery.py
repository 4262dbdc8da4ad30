# SPDX-License-Identifier: MIT
"""Discovery over mDNS/DNS-SD as SiLA 2 describes it (Debian's python3-zeroconf): the service
_sila._tcp, named by the server's UUID, with its version, name and description in the TXT
record, and the certificate clients pin as ca0, ca1 ... (its PEM lines)."""
import ipaddress
import logging
import socket
import threading
import time

from zeroconf import IPVersion, ServiceBrowser, ServiceInfo, Zeroconf

SERVICE = "_sila._tcp.local."
log = logging.getLogger("fbrl-station")


def _addresses(host):
    try:
        ip = ipaddress.ip_address(host)
    except ValueError:
        ip = ipaddress.ip_address(socket.gethostbyname(host))
    if not ip.is_unspecified:
        return [ip.packed]
    found = {ipaddress.ip_address("127.0.0.1").packed}
    try:
        for info in socket.getaddrinfo(socket.gethostname(), None, socket.AF_INET):
            found.add(ipaddress.ip_address(info[4][0]).packed)
    except socket.gaierror:
        pass  # no name for this host: loopback only
    return sorted(found)


def txt_record(version, name, description, cert_pem):
    props = {"version": version, "server_name": name, "description": description[:200]}
    if cert_pem:
        for i, line in enumerate(cert_pem.decode("ascii").strip().splitlines()):
            props["ca%d" % i] = line
    return props


class Announcer:
    """The station's record, registered in the background (probing takes a second or two) and
    withdrawn on close."""

    def __init__(self, uuid, host, port, props):
        self.info = ServiceInfo(SERVICE, "%s.%s" % (uuid, SERVICE), addresses=_addresses(host), port=port,
                                properties=props, server="%s.local." % socket.gethostname().split(".")[0])
        self.zc = None
        self._thread = threading.Thread(target=self._register, name="fbrl-mdns", daemon=True)
        self._thread.start()

    def _register(self):
        try:
            self.zc = Zeroconf(ip_version=IPVersion.V4Only)
            self.zc.register_service(self.info, allow_name_change=False)
        except Exception as e:  # no multicast here: the station still serves, undiscovered
            log.warning("discovery: could not announce the station over mDNS: %s", e)

    def update(self, props):
        """A new TXT record (the server's name changed)."""
        self._thread.join()
        if self.zc is not None:
            self.info.properties = props
            self.zc.update_service(self.info)

    def close(self):
        self._thread.join()
        if self.zc is not None:
            try:
                self.zc.unregister_service(self.info)
            finally:
                self.zc.close()


def browse(seconds):
    """The SiLA servers announced on the network within seconds: {uuid: ServiceInfo}."""
    zc = Zeroconf(ip_version=IPVersion.V4Only)
    found = {}

    class Listener:
        def add_service(self, z, type_, name):
            info = z.get_service_info(type_, name, timeout=2000)
            if info is not None:
                found[name[:-len(SERVICE) - 1]] = info

        update_service = add_service

        def remove_service(self, z, type_, name):
            found.pop(name[:-len(SERVICE) - 1], None)

    ServiceBrowser(zc, SERVICE, Listener())
    time.sleep(seconds)
    zc.close()
    return found
