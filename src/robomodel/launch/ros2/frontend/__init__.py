"""The XML and YAML launch front-ends (launch_xml / launch_yaml)."""
