#!/usr/bin/env bash
# Makes throwaway TLS material in DIR for the tests: a CA (ca.crt) signing a
# server certificate for IP 127.0.0.1 (server.crt/.key) and a client
# certificate (client.crt/.key), and another CA (other-ca.crt) signing
# other-client.crt/.key, for "wrong CA" cases. Valid one day; never reused.
set -euo pipefail
dir=$1
cd "$dir"
new_key() { openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out "$1" 2>/dev/null; }
new_ca() {  # NAME CN
  new_key "$1.key"
  openssl req -x509 -new -key "$1.key" -days 1 -subj "/CN=$2" -out "$1.crt" \
    -addext basicConstraints=critical,CA:TRUE -addext keyUsage=critical,keyCertSign,cRLSign
}
sign() {  # NAME CA CN EXTENSIONS
  new_key "$1.key"
  openssl req -new -key "$1.key" -subj "/CN=$3" -out "$1.csr"
  openssl x509 -req -in "$1.csr" -CA "$2.crt" -CAkey "$2.key" -CAcreateserial -days 1 \
    -out "$1.crt" -extfile <(printf '%s\n' "$4") 2>/dev/null
  rm "$1.csr"
}
new_ca ca scallop-test-ca
new_ca other-ca scallop-other-ca
sign server ca 127.0.0.1 $'subjectAltName=IP:127.0.0.1\nextendedKeyUsage=serverAuth'
sign client ca scallop-test-client 'extendedKeyUsage=clientAuth'
sign other-client other-ca scallop-other-client 'extendedKeyUsage=clientAuth'
