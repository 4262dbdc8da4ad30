# SPDX-License-Identifier: MIT
"""The station's TLS identity: a self-signed certificate made at the first start and kept in
the data folder, carrying the server's UUID as SiLA 2 asks (extension 1.3.6.1.4.1.58583, the
UUID's text), valid for the names and addresses clients reach it by. Clients pin it: they
trust this certificate itself (docs/sila.md), taken from the data folder or from the
discovery record. The page (--http with --lab) serves HTTPS and WSS with the same pair.

X.509 is outside libsodium; the key and certificate are made with Debian's
python3-cryptography (OpenSSL), gRPC's own TLS carries the connection."""
import datetime
import ipaddress
import socket

from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.x509.oid import NameOID

SILA_UUID_OID = x509.ObjectIdentifier("1.3.6.1.4.1.58583")
KEY_FILE, CERT_FILE = "key.pem", "cert.pem"
VALID_DAYS = 3650


def names_for(*hosts):
    """The DNS names and IP addresses a certificate for servers bound to hosts covers (the
    SiLA side's and the page's: one certificate for both)."""
    dns = {"localhost", socket.gethostname()}
    fqdn = socket.getfqdn()
    if fqdn:
        dns.add(fqdn)
    ips = {"127.0.0.1", "::1"}
    for host in hosts:
        try:
            if not ipaddress.ip_address(host).is_unspecified:
                ips.add(host)
        except ValueError:
            dns.add(host)
    return sorted(dns), sorted(ips)


def _covers(cert, uuid, dns, ips):
    try:
        ext = cert.extensions.get_extension_for_oid(SILA_UUID_OID).value.value
        san = cert.extensions.get_extension_for_class(x509.SubjectAlternativeName).value
    except x509.ExtensionNotFound:
        return False
    have_dns = set(san.get_values_for_type(x509.DNSName))
    have_ips = {str(a) for a in san.get_values_for_type(x509.IPAddress)}
    return ext == uuid.encode("ascii") and set(dns) <= have_dns and set(ips) <= have_ips


def identity(data, uuid, *hosts):
    """(private key PEM, certificate PEM) for the station: the kept pair when it carries this
    UUID and covers the hosts, else a new pair (kept, owner-only)."""
    dns, ips = names_for(*hosts)
    try:
        with open(data.file(KEY_FILE), "rb") as f:
            key_pem = f.read()
        with open(data.file(CERT_FILE), "rb") as f:
            cert_pem = f.read()
        if _covers(x509.load_pem_x509_certificate(cert_pem), uuid, dns, ips):
            return key_pem, cert_pem
    except (FileNotFoundError, ValueError):
        pass  # none yet, or not readable as a certificate: make a new one
    key = ec.generate_private_key(ec.SECP256R1())
    name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "fbrl-station " + uuid),
                      x509.NameAttribute(NameOID.ORGANIZATION_NAME, "libfbrl")])
    now = datetime.datetime.now(datetime.timezone.utc)
    san = [x509.DNSName(d) for d in dns] + [x509.IPAddress(ipaddress.ip_address(i)) for i in ips]
    cert = (x509.CertificateBuilder().subject_name(name).issuer_name(name).public_key(key.public_key())
            .serial_number(x509.random_serial_number())
            .not_valid_before(now - datetime.timedelta(minutes=5))
            .not_valid_after(now + datetime.timedelta(days=VALID_DAYS))
            .add_extension(x509.SubjectAlternativeName(san), critical=False)
            .add_extension(x509.BasicConstraints(ca=True, path_length=0), critical=True)
            .add_extension(x509.UnrecognizedExtension(SILA_UUID_OID, uuid.encode("ascii")), critical=False)
            .sign(key, hashes.SHA256()))
    key_pem = key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                serialization.NoEncryption())
    cert_pem = cert.public_bytes(serialization.Encoding.PEM)
    data.write(KEY_FILE, key_pem)
    data.write(CERT_FILE, cert_pem, mode=0o644)
    return key_pem, cert_pem


def uuid_of(cert_pem):
    """The SiLA server UUID a certificate carries (for clients and tests), or None."""
    cert = x509.load_pem_x509_certificate(cert_pem)
    try:
        return cert.extensions.get_extension_for_oid(SILA_UUID_OID).value.value.decode("ascii")
    except x509.ExtensionNotFound:
        return None
